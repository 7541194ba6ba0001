#include "input/trajectory_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/file_error.hpp"

namespace mallet::input {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

bool parse_double(std::string_view text, double& out) {
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

Trajectory parse_trajectory_csv(std::string_view text, const std::string& name) {
  Trajectory out;
  int col_t = -1, col_x = -1, col_y = -1;
  std::size_t columns = 0;
  std::uint32_t line_no = 0;
  std::size_t pos = 0;
  double previous_t = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line = trim(text.substr(pos, nl == std::string_view::npos ? nl : nl - pos));
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string_view> fields = split(line);
    if (col_t < 0) {  // the header
      for (std::size_t i = 0; i < fields.size(); ++i) {
        if (fields[i] == "t") col_t = static_cast<int>(i);
        else if (fields[i] == "x") col_x = static_cast<int>(i);
        else if (fields[i] == "y") col_y = static_cast<int>(i);
      }
      for (auto [col, label] : {std::pair{col_t, "t"}, {col_x, "x"}, {col_y, "y"}}) {
        if (col < 0)
          throw FileError(name, line_no, 0,
                          std::string("missing column \"") + label +
                              "\" (the header must name the columns t,x,y)");
      }
      columns = fields.size();
      continue;
    }
    if (fields.size() < columns)
      throw FileError(name, line_no, 0, "expected " + std::to_string(columns) + " fields, got " +
                                            std::to_string(fields.size()));
    double v[3];
    const int cols[3] = {col_t, col_x, col_y};
    const char* labels[3] = {"t", "x", "y"};
    for (int k = 0; k < 3; ++k) {
      if (!parse_double(fields[cols[k]], v[k]))
        throw FileError(name, line_no, 0,
                        std::string("column ") + labels[k] + ": \"" + std::string(fields[cols[k]]) +
                            "\" is not a number");
    }
    if (!std::isfinite(v[0])) throw FileError(name, line_no, 0, "t is not a finite number");
    if (v[0] < 0) throw FileError(name, line_no, 0, "t must be >= 0 seconds");
    if (!out.samples.empty() && v[0] < previous_t) {
      std::ostringstream msg;
      msg << "t = " << v[0] << " is before the previous row's t = " << previous_t
          << " (times must not decrease)";
      throw FileError(name, line_no, 0, msg.str());
    }
    const auto t_ns = from_seconds(v[0]);
    if (!t_ns) throw FileError(name, line_no, 0, "t is out of range");
    previous_t = v[0];
    out.samples.push_back({*t_ns, v[1], v[2]});
  }
  if (col_t < 0) throw FileError(name, 0, 0, "empty file (expected a header t,x,y and rows)");
  if (out.samples.empty()) throw FileError(name, 0, 0, "no data rows after the header");
  return out;
}

Trajectory read_trajectory_csv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), 0, 0, "cannot open (does it exist?)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_trajectory_csv(buffer.str(), path.string());
}

}  // namespace mallet::input
