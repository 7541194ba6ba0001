#pragma once
// One reader for every CSV file the project reads: the study's results, recorded
// trajectories, calibration points, and the kiosk's own events.csv and cursor.csv. A file is
// a header line naming its columns, then rows of comma-separated fields. '\r' line ends are
// accepted and blank lines skipped. Where a format allows them ("hand-written"), '#' lines are
// comments and fields are trimmed of spaces and tabs. Every problem is one FileError,
// FILE:LINE: problem, worded the same whichever file it is:
//   missing column "t" (HINT)            expected 3 fields, got 2
//   t: "x" is not a number               empty file (HINT)
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mallet::csv {

struct Options {
  bool hand_written = false;   //!< '#' comment lines skipped and fields trimmed
  bool extra_fields = false;   //!< a row may have more fields than the header (they are ignored)
  //! A last line without its '\n' (the program stopped while writing it) is dropped with a
  //! warning instead of refused: for the files the program appends to.
  bool incomplete_last_line = false;
};

struct Row {
  std::uint32_t line = 0;  //!< 1-based, in the file
  std::vector<std::string> fields;
  const std::string& operator[](std::size_t column) const { return fields.at(column); }
};

struct Table {
  std::string file;                   //!< what messages call it
  std::vector<std::string> header;    //!< empty: the file holds no header line
  std::string header_text;            //!< the header line as written
  std::uint32_t header_line = 0;      //!< its line in the file
  std::vector<Row> rows;
  std::vector<std::string> warnings;  //!< "FILE:LINE: ..." (an incomplete last line dropped)
  std::uintmax_t complete_bytes = 0;  //!< the text's length up to its last complete line

  bool has_header() const { return !header.empty(); }
  std::optional<std::size_t> find(std::string_view name) const;
  //! The column's index; `missing column "NAME" (HINT)` at the header's line when absent,
  //! `empty file (no header line)` when there is no header at all.
  std::size_t column(std::string_view name, std::string_view hint = {}) const;
  //! A field as a number (the whole field; a leading '+' allowed);
  //! `LABEL: "FIELD" is not a number` at the row's line otherwise.
  double number(const Row& row, std::size_t column, std::string_view label) const;
  //! Row `row`'s field in `column` as a number, labelled by the column's name.
  double number(std::size_t row, std::size_t column) const { return number(rows.at(row), column, header.at(column)); }
  //! Fails with FILE:LINE: message.
  [[noreturn]] void fail(std::uint32_t line, const std::string& message) const;
};

Table parse(std::string_view text, std::string file, Options options = {});
//! The file read whole; `FILE: cannot open (does it exist?)` when it cannot be.
Table read(const std::filesystem::path& path, Options options = {});

}  // namespace mallet::csv
