#pragma once
// A small reader for the CSV files mallet itself writes (events.csv, cursor.csv):
// a header row, then rows of fields. Used by `mallet analyze` and the tests.
#include <filesystem>
#include <string>
#include <vector>

namespace mallet::app {

struct CsvTable {
  std::string file;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  //! Index of a column; throws FileError naming the file if it is missing.
  std::size_t column(const std::string& name) const;
  //! A field as a number; throws FileError with the line if it is not one.
  double number(std::size_t row, std::size_t column) const;
};

CsvTable read_csv_table(const std::filesystem::path& path);

}  // namespace mallet::app
