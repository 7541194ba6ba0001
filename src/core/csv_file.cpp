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
  std::uint32_t line_no = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    ++line_no;
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos && options.incomplete_last_line) {
      t.warnings.push_back(t.file + ":" + std::to_string(line_no) +
                           ": incomplete last line ignored (the program stopped while writing it)");
      break;
    }
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    t.complete_bytes = pos;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (options.hand_written) line = text::trim(line);
    if (line.empty() || (options.hand_written && line.front() == '#')) continue;
    std::vector<std::string> fields;
    if (options.hand_written) {
      for (std::string_view f : text::split_fields(line)) fields.emplace_back(f);
    } else {
      std::size_t start = 0;
      for (std::size_t comma; (comma = line.find(',', start)) != std::string_view::npos; start = comma + 1)
        fields.emplace_back(line.substr(start, comma - start));
      fields.emplace_back(line.substr(start));
    }
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
