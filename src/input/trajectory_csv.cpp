#include "input/trajectory_csv.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "core/file_error.hpp"
#include "core/text_lines.hpp"

namespace mallet::input {

namespace {

}  // namespace

Trajectory parse_trajectory_csv(std::string_view text, const std::string& name) {
  Trajectory out;
  int col_t = -1, col_x = -1, col_y = -1;
  std::size_t columns = 0;
  double previous_t = 0;
  text::Lines lines(text);
  while (auto raw = lines.next()) {
    const std::uint32_t line_no = lines.number();
    const std::string_view line = text::trim(*raw);
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string_view> fields = text::split_fields(line);
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
      if (!text::parse_double(fields[cols[k]], v[k]))
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
  return parse_trajectory_csv(text::read_file(path), path.string());
}

}  // namespace mallet::input
