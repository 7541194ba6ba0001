#pragma once
// Writing the TOML files Mallet keeps (calibration.toml, actuator_eq.toml): a basic string
// with its escapes, a number that reads back as the same double, and text safe inside a
// one-line comment.
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace mallet::toml_text {

//! 17 significant digits: a load gives back the same double.
inline std::string exact_number(double v) { return fmt::format("{:.17g}", v); }

//! A TOML basic string, quoted, with '"', '\' and control characters escaped.
inline std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

//! `s` with its control characters made spaces: safe after a '#'.
inline std::string comment(std::string_view s) {
  std::string out(s);
  for (char& ch : out)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = ' ';
  return out;
}

}  // namespace mallet::toml_text
