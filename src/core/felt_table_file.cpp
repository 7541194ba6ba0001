#include "core/felt_table_file.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/csv_file.hpp"

namespace mallet {

namespace {

std::string field(double v) { return std::isnan(v) ? std::string() : fmt::format("{}", v); }

}  // namespace

std::string format_felt_table(const std::vector<FeltRecord>& rows) {
  std::string out = std::string(kFeltHeader) + "\n";
  for (const FeltRecord& r : rows)
    out += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", r.material, r.speed_m_per_s, r.table_decay_per_s,
                       r.table_freq_hz, field(r.decay_before), field(r.freq_before), field(r.decay_after),
                       field(r.freq_after), r.calibration, r.verified_utc);
  return out;
}

std::vector<FeltRecord> read_felt_table(const std::filesystem::path& path) {
  const csv::Table t = csv::read(path);
  const std::string hint = std::string("the header is ") + kFeltHeader;
  const auto col = [&](const char* name) { return t.column(name, hint); };
  const std::size_t material = col("material"), speed = col("speed_m_per_s"), tb = col("table_decay_per_s"),
                    tf = col("table_freq_hz"), db = col("decay_before"), fb = col("freq_before"),
                    da = col("decay_after"), fa = col("freq_after"), cal = col("calibration"),
                    when = col("verified_utc");
  const auto maybe = [&](const csv::Row& row, std::size_t c) {
    return row[c].empty() ? std::nan("") : t.number(row, c, t.header[c]);
  };
  std::vector<FeltRecord> out;
  for (const csv::Row& row : t.rows) {
    FeltRecord r;
    r.material = row[material];
    r.speed_m_per_s = t.number(row, speed, "speed_m_per_s");
    r.table_decay_per_s = t.number(row, tb, "table_decay_per_s");
    r.table_freq_hz = t.number(row, tf, "table_freq_hz");
    r.decay_before = maybe(row, db);
    r.freq_before = maybe(row, fb);
    r.decay_after = maybe(row, da);
    r.freq_after = maybe(row, fa);
    r.calibration = row[cal];
    r.verified_utc = row[when];
    out.push_back(r);
  }
  return out;
}

}  // namespace mallet
