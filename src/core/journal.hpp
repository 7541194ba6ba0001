#pragma once
// One way to write a line for the journal: on stderr, with its syslog priority in front
// ("<3>" error, "<4>" warning, "<5>" notice, "<6>" info, "<7>" debug), which journald reads
// as the line's priority (the unit's SyslogLevelPrefix=, on by default) and a terminal shows
// as it is. The text is formatted by {fmt} ("{}" and "{:.1f}", checked at compile time).
#include <fmt/format.h>

namespace mallet::journal {

//! The line formatted once, straight after its priority, and written whole in one call, so
//! that lines of several threads never interleave.
void write(int priority, fmt::string_view format, fmt::format_args args);

//! journal::error(...), warning, notice, info: the line formatted by {fmt}, at that priority.
template <int Priority>
struct Writer {
  template <typename... Args>
  void operator()(fmt::format_string<Args...> format, Args&&... args) const {
    write(Priority, fmt::string_view(format), fmt::make_format_args(args...));
  }
};
inline constexpr Writer<3> error;
inline constexpr Writer<4> warning;
inline constexpr Writer<5> notice;
inline constexpr Writer<6> info;

}  // namespace mallet::journal
