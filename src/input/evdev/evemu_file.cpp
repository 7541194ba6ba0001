#include "input/evdev/evemu_file.hpp"

#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <cstdint>

#include <fmt/format.h>

#include "core/file_error.hpp"
#include "core/text_lines.hpp"

namespace mallet::input::evdev {

namespace {

//! The next blank-separated field of `line` (advancing it), or empty at the end.
std::string_view next_field(std::string_view& line) {
  line = text::trim(line);
  std::size_t end = 0;
  while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
  const std::string_view field = line.substr(0, end);
  line.remove_prefix(end);
  return field;
}

template <typename T>
bool parse_whole(std::string_view text, T& out, int base = 10) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out, base);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

std::vector<input_event> parse_evemu_events(std::string_view text, const std::string& name) {
  std::vector<input_event> out;
  text::Lines lines(text);
  while (auto raw = lines.next()) {
    std::string_view line = text::trim(*raw);
    if (!line.starts_with("E:")) continue;
    line.remove_prefix(2);
    const std::uint32_t line_no = lines.number();
    const auto fail = [&](const std::string& what) {
      throw FileError(name, line_no, 0, what + " (expected \"E: SECONDS.MICROSECONDS TYPE CODE VALUE\")");
    };
    const std::string_view time = next_field(line);
    const std::string_view type = next_field(line);
    const std::string_view code = next_field(line);
    const std::string_view value = next_field(line);
    const std::size_t dot = time.find('.');
    std::int64_t sec = 0, usec = 0;
    if (dot == std::string_view::npos || !parse_whole(time.substr(0, dot), sec) || sec < 0 ||
        time.size() - dot - 1 != 6 || !parse_whole(time.substr(dot + 1), usec) || usec < 0) {
      fail("bad time \"" + std::string(time) + "\"");
    }
    std::uint32_t type_value = 0, code_value = 0;
    if (!parse_whole(type, type_value, 16) || type_value > 0xffff) fail("bad type \"" + std::string(type) + "\"");
    if (!parse_whole(code, code_value, 16) || code_value > 0xffff) fail("bad code \"" + std::string(code) + "\"");
    std::int32_t event_value = 0;
    if (!parse_whole(value, event_value)) fail("bad value \"" + std::string(value) + "\"");
    input_event event{};
    event.input_event_sec = static_cast<decltype(event.input_event_sec)>(sec);
    event.input_event_usec = static_cast<decltype(event.input_event_usec)>(usec);
    event.type = static_cast<std::uint16_t>(type_value);
    event.code = static_cast<std::uint16_t>(code_value);
    event.value = event_value;
    out.push_back(event);
  }
  return out;
}

std::vector<input_event> read_evemu_events(const std::filesystem::path& path) {
  return parse_evemu_events(text::read_file(path), path.string());
}

std::string format_evemu_event(const input_event& event) {
  return fmt::format("E: {}.{:06} {:04x} {:04x} {:04}", static_cast<std::int64_t>(event.input_event_sec),
                     static_cast<std::int64_t>(event.input_event_usec), static_cast<unsigned>(event.type),
                     static_cast<unsigned>(event.code), static_cast<int>(event.value));
}

}  // namespace mallet::input::evdev
