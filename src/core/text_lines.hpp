#pragma once
// Small helpers shared by the strict text readers (trajectories, calibration points,
// hex reports, replay files): lines with their numbers, trimmed comma fields, numbers
// parsed whole or not at all.
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/file_error.hpp"

namespace mallet::text {

//! The whole file as bytes; FileError "FILE: cannot open (does it exist?)" if it cannot be read.
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), 0, 0, "cannot open (does it exist?)");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

//! The comma-separated fields of a line, each trimmed (`trimmed` false: kept as written).
inline std::vector<std::string_view> split_fields(std::string_view line, bool trimmed = true) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view field = line.substr(start, comma == std::string_view::npos ? comma : comma - start);
    out.push_back(trimmed ? trim(field) : field);
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

//! The whole of `text` as a double (a leading '+' allowed; "nan"/"inf" accepted).
inline bool parse_double(std::string_view text, double& out) {
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size();
}

//! Walks a text line by line (a trailing '\r' removed), counting from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  std::optional<std::string_view> next() {
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t nl = text_.find('\n', pos_);
    std::string_view line = text_.substr(pos_, nl == std::string_view::npos ? std::string_view::npos : nl - pos_);
    pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
    ended_ = nl != std::string_view::npos;
    ++number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }
  std::uint32_t number() const { return number_; }  //!< of the line last returned
  //! Whether the line last returned ended with its '\n' (a file cut mid-write does not).
  bool ended() const { return ended_; }
  //! The bytes of the text up to the end of the line last returned.
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::uint32_t number_ = 0;
  bool ended_ = false;
};

}  // namespace mallet::text
