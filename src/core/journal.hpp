#pragma once
// One way to write a line for the journal: on stderr, with its syslog priority in front
// ("<3>" error, "<4>" warning, "<5>" notice, "<6>" info, "<7>" debug), which journald reads
// as the line's priority (the unit's SyslogLevelPrefix=, on by default) and a terminal shows
// as it is. The text is formatted by {fmt} ("{}" and "{:.1f}", checked at compile time).
#include <string_view>
#include <utility>

#include <fmt/format.h>

namespace mallet::journal {

//! The whole line in one write, so that lines of several threads never interleave.
void write(int priority, std::string_view text);

template <typename... Args>
void error(fmt::format_string<Args...> format, Args&&... args) {
  write(3, fmt::format(format, std::forward<Args>(args)...));
}
template <typename... Args>
void warning(fmt::format_string<Args...> format, Args&&... args) {
  write(4, fmt::format(format, std::forward<Args>(args)...));
}
template <typename... Args>
void notice(fmt::format_string<Args...> format, Args&&... args) {
  write(5, fmt::format(format, std::forward<Args>(args)...));
}
template <typename... Args>
void info(fmt::format_string<Args...> format, Args&&... args) {
  write(6, fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace mallet::journal
