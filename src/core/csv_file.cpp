#include "core/csv_file.hpp"

#include "core/file_error.hpp"
#include "core/text_lines.hpp"

namespace mallet::csv {

std::optional<std::size_t> Table::find(std::string_view name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  return std::nullopt;
}

void Table::fail(std::uint32_t line, const std::string& message) const { throw FileError(file, line, 0, message); }

std::size_t Table::column(std::string_view name, std::string_view hint) const {
  if (const auto i = find(name)) return *i;
  if (!has_header()) fail(0, "empty file (no header line)");
  std::string message = "missing column \"" + std::string(name) + "\"";
  if (!hint.empty()) message += " (" + std::string(hint) + ")";
  fail(header_line, message);
}

double Table::number(const Row& row, std::size_t column, std::string_view label) const {
  const std::string& s = row.fields.at(column);
  double v = 0;
  if (!text::parse_double(s, v)) fail(row.line, std::string(label) + ": \"" + s + "\" is not a number");
  return v;
}

Table parse(std::string_view text, std::string file, Options options) {
  Table t;
  t.file = std::move(file);
  text::Lines lines(text);
  while (std::optional<std::string_view> next = lines.next()) {
    const std::uint32_t line_no = lines.number();
    if (!lines.ended() && options.incomplete_last_line) {
      t.warnings.push_back(t.file + ":" + std::to_string(line_no) +
                           ": incomplete last line ignored (the program stopped while writing it)");
      break;
    }
    t.complete_bytes = lines.offset();
    const std::string_view line = options.hand_written ? text::trim(*next) : *next;
    if (line.empty() || (options.hand_written && line.front() == '#')) continue;
    std::vector<std::string> fields;
    for (std::string_view f : text::split_fields(line, options.hand_written)) fields.emplace_back(f);
    if (!t.has_header()) {
      t.header = std::move(fields);
      t.header_text = std::string(line);
      t.header_line = line_no;
      continue;
    }
    if (fields.size() < t.header.size() || (fields.size() > t.header.size() && !options.extra_fields))
      t.fail(line_no, "expected " + std::to_string(t.header.size()) + " fields, got " + std::to_string(fields.size()));
    t.rows.push_back({line_no, std::move(fields)});
  }
  return t;
}

Table read(const std::filesystem::path& path, Options options) {
  return parse(text::read_file(path), path.string(), options);
}

}  // namespace mallet::csv
