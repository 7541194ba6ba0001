#include "input/trajectory_csv.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "core/csv_file.hpp"
#include "core/file_error.hpp"
#include "core/text_lines.hpp"

namespace mallet::input {

Trajectory parse_trajectory_csv(std::string_view text, const std::string& name) {
  const csv::Table table = csv::parse(text, name, {.hand_written = true, .extra_fields = true});
  if (!table.has_header()) throw FileError(name, 0, 0, "empty file (expected a header t,x,y and rows)");
  constexpr std::string_view kHint = "the header must name the columns t,x,y";
  const std::size_t cols[3] = {table.column("t", kHint), table.column("x", kHint), table.column("y", kHint)};
  Trajectory out;
  double previous_t = 0;
  for (const csv::Row& row : table.rows) {
    double v[3];
    for (int k = 0; k < 3; ++k) v[k] = table.number(row, cols[k], table.header[cols[k]]);
    if (!std::isfinite(v[0])) table.fail(row.line, "t is not a finite number");
    if (v[0] < 0) table.fail(row.line, "t must be >= 0 seconds");
    if (!out.samples.empty() && v[0] < previous_t) {
      std::ostringstream msg;
      msg << "t = " << v[0] << " is before the previous row's t = " << previous_t << " (times must not decrease)";
      table.fail(row.line, msg.str());
    }
    const auto t_ns = from_seconds(v[0]);
    if (!t_ns) table.fail(row.line, "t is out of range");
    previous_t = v[0];
    out.samples.push_back({*t_ns, v[1], v[2]});
  }
  if (out.samples.empty()) throw FileError(name, 0, 0, "no data rows after the header");
  return out;
}

Trajectory read_trajectory_csv(const std::filesystem::path& path) {
  return parse_trajectory_csv(text::read_file(path), path.string());
}

}  // namespace mallet::input
