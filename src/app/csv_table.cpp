#include "app/csv_table.hpp"

#include <charconv>
#include <fstream>

#include "core/file_error.hpp"

namespace mallet::app {

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  throw FileError(file, 1, 0, "missing column \"" + name + "\"");
}

double CsvTable::number(std::size_t row, std::size_t col) const {
  const std::string& s = rows.at(row).at(col);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size())
    throw FileError(file, static_cast<std::uint32_t>(row + 2), 0, "\"" + s + "\" is not a number");
  return v;
}

CsvTable read_csv_table(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path.string(), 0, 0, "cannot open (does it exist?)");
  CsvTable t;
  t.file = path.string();
  std::string line;
  std::uint32_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
      fields.push_back(line.substr(start, comma - start));
    fields.push_back(line.substr(start));
    if (t.header.empty()) {
      t.header = std::move(fields);
    } else {
      if (fields.size() != t.header.size())
        throw FileError(t.file, line_no, 0, "expected " + std::to_string(t.header.size()) + " fields, got " +
                                                std::to_string(fields.size()));
      t.rows.push_back(std::move(fields));
    }
  }
  if (t.header.empty()) throw FileError(t.file, 0, 0, "empty file");
  return t;
}

}  // namespace mallet::app
