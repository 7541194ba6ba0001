#pragma once
// A problem in a file a person wrote or a device produced (config, scene, trajectory,
// recording), reported as one line they can act on:
//   config/materials.toml:12:17: material.wood.visual.decay_per_s: must be >= 0, got -8
// Control characters in the file name or the message (a value quoted from the file) are
// shown escaped, so the message is always exactly one line.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace mallet {

//! Where in a file something was written (line and column 1-based; 0 = unknown).
struct FilePlace {
  std::string file;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

class FileError : public std::runtime_error {
 public:
  FileError(const FilePlace& at, const std::string& message) : FileError(at.file, at.line, at.column, message) {}
  FileError(std::string file, std::uint32_t line, std::uint32_t column, const std::string& message)
      : std::runtime_error(format(file, line, column, message)),
        file_(std::move(file)),
        line_(line),
        column_(column) {}

  const std::string& file() const { return file_; }
  std::uint32_t line() const { return line_; }      //!< 1-based; 0 = the file as a whole
  std::uint32_t column() const { return column_; }  //!< 1-based; 0 = unknown

 private:
  //! `text` with each control character written as an escape (\n, \r, \t, \xHH): a file
  //! name or a quoted piece of a file can never break the message's one line.
  static void append_printable(std::string& out, const std::string& text) {
    static constexpr char kHex[] = "0123456789abcdef";
    for (const char ch : text) {
      const auto c = static_cast<unsigned char>(ch);
      if (c >= 0x20 && c != 0x7f) {
        out += ch;
      } else if (ch == '\n' || ch == '\r' || ch == '\t') {
        out += '\\';
        out += ch == '\n' ? 'n' : ch == '\r' ? 'r' : 't';
      } else {
        out += "\\x";
        out += kHex[c >> 4];
        out += kHex[c & 0xf];
      }
    }
  }

  static std::string format(const std::string& file, std::uint32_t line, std::uint32_t column,
                            const std::string& message) {
    std::string out;
    append_printable(out, file);
    if (line > 0) {
      out += ':';
      out += std::to_string(line);
      if (column > 0) {
        out += ':';
        out += std::to_string(column);
      }
    }
    out += ": ";
    append_printable(out, message);
    return out;
  }

  std::string file_;
  std::uint32_t line_;
  std::uint32_t column_;
};

//! A configuration or scene file that cannot be used.
using ConfigError = FileError;

}  // namespace mallet
