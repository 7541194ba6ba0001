#include "core/actuator_eq_file.hpp"

#include <bit>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/config/toml_reader.hpp"
#include "core/toml_text.hpp"

namespace mallet {

namespace {

constexpr std::int64_t kEqFormatVersion = 1;

std::optional<std::pair<std::string, std::string>> problem_of(const ActuatorEq& e) {
  if (!(e.sample_rate_hz >= 8000 && e.sample_rate_hz <= 384000))
    return std::pair{std::string("sample_rate_hz"), std::string("must be 8000 to 384000")};
  if (e.taps.size() < 16 || e.taps.size() > 8192)
    return std::pair{std::string("taps"), fmt::format("must hold 16 to 8192 numbers, not {}", e.taps.size())};
  for (double v : e.taps)
    if (!std::isfinite(v) || std::abs(v) > 1e3) return std::pair{std::string("taps"), std::string("must be finite numbers within ±1000")};
  if (e.frequency_hz.size() != e.magnitude_db.size() || e.frequency_hz.size() != e.phase_deg.size())
    return std::pair{std::string("magnitude_db"), std::string("frequency_hz, magnitude_db and phase_deg must be as long as each other")};
  if (!(e.gain_limit_db > 0 && e.gain_limit_db <= 40))
    return std::pair{std::string("gain_limit_db"), std::string("must be above 0 and at most 40")};
  if (!(e.band_low_hz > 0 && e.band_low_hz < e.band_high_hz))
    return std::pair{std::string("usable_band_hz"), std::string("must be [low, high] with 0 < low < high")};
  if (!std::isfinite(e.latency_samples) || std::abs(e.latency_samples) > 8192)
    return std::pair{std::string("latency_samples"), std::string("must be a finite number within ±8192")};
  return std::nullopt;
}

std::string list(const std::vector<double>& v, int per_line) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i % static_cast<std::size_t>(per_line) == 0) out += "\n  ";
    out += toml_text::exact_number(v[i]) + ", ";
  }
  return out + "\n]";
}

ActuatorEq read_eq(const toml::table& root, const std::string& name) {
  config::TableReader top(root, name);
  const std::int64_t version = top.integer("format_version");
  if (version != kEqFormatVersion)
    top.fail("format_version", fmt::format("this mallet reads format_version = {}, got {}", kEqFormatVersion, version));
  ActuatorEq e;
  e.created_utc = top.string_or("created_utc", "");
  e.created_by = top.string_or("created_by", "");
  e.sensor = top.string_or("sensor", "");
  e.sample_rate_hz = static_cast<int>(top.integer("sample_rate_hz"));
  const auto pair = [&](std::string_view key, double& a, double& b) {
    const std::vector<double> v = top.numbers(key);
    if (v.size() != 2) top.fail(key, "expected [low, high]");
    a = v[0];
    b = v[1];
  };
  pair("sweep_hz", e.sweep_low_hz, e.sweep_high_hz);
  e.level_db = top.number("level_db");
  e.resonance_hz = top.number("resonance_hz");
  e.resonance_db = top.number("resonance_db");
  pair("usable_band_hz", e.band_low_hz, e.band_high_hz);
  e.delay_ms = top.number("delay_ms");
  if (top.has("round_trip_ms")) e.round_trip_ms = top.number("round_trip_ms");
  e.gain_limit_db = top.number("gain_limit_db");
  e.target_db = top.number("target_db");
  e.latency_samples = top.number("latency_samples");
  if (auto r = top.optional_table("response")) {
    e.frequency_hz = r->numbers("frequency_hz");
    e.magnitude_db = r->numbers("magnitude_db");
    e.phase_deg = r->numbers("phase_deg");
    r->finish();
  }
  config::TableReader inverse = top.table("inverse");
  e.taps = inverse.numbers("taps");
  inverse.finish();
  top.finish();
  if (const auto p = problem_of(e)) {
    if (p->first == "taps") inverse.fail("taps", p->second);
    top.fail(p->first == "magnitude_db" ? "response" : p->first, p->second);
  }
  return e;
}

}  // namespace

std::string ActuatorEq::hash() const {
  std::uint64_t h = 0xcbf29ce484222325ull;
  const auto add = [&h](std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= (v >> (8 * i)) & 0xff;
      h *= 0x100000001b3ull;
    }
  };
  add(static_cast<std::uint64_t>(sample_rate_hz));
  for (double t : taps) add(std::bit_cast<std::uint64_t>(t));
  return fmt::format("{:016x}", h);
}

int ActuatorEq::alignment_samples() const {
  return latency_samples > 0 ? static_cast<int>(std::lround(latency_samples)) : 0;
}

ActuatorEq parse_actuator_eq(std::string_view text, const std::string& name) {
  return read_eq(config::parse_text(text, name), name);
}

ActuatorEq load_actuator_eq(const std::filesystem::path& path) {
  return read_eq(config::parse_file(path), path.string());
}

std::string format_actuator_eq(const ActuatorEq& e) {
  using toml_text::exact_number;
  std::string out;
  out += "# Mallet actuator calibration: the chain amplifier -> voice coil -> stick -> sensor as\n";
  out += "# measured by " + toml_text::comment(e.created_by.empty() ? "mallet" : e.created_by) + " at " +
         toml_text::comment(e.created_utc.empty() ? "an unknown time" : e.created_utc) + ",\n";
  out += "# and the inverse the kiosk applies to the actuator channel ([actuator] equalize).\n";
  out += "# Measure again (mallet calibrate actuator) whenever the stick, the actuator or the amplifier changes.\n";
  out += fmt::format("format_version = {}\n", kEqFormatVersion);
  out += "created_utc = " + toml_text::quoted(e.created_utc) + "\n";
  out += "created_by = " + toml_text::quoted(e.created_by) + "\n";
  out += "sensor = " + toml_text::quoted(e.sensor) + "  # what recorded it\n";
  out += fmt::format("sample_rate_hz = {}  # the taps are for this rate only\n", e.sample_rate_hz);
  out += "sweep_hz = [" + exact_number(e.sweep_low_hz) + ", " + exact_number(e.sweep_high_hz) + "]\n";
  out += "level_db = " + exact_number(e.level_db) + "  # the sweep's peak, dB of full scale\n";
  out += "resonance_hz = " + exact_number(e.resonance_hz) + "\n";
  out += "resonance_db = " + exact_number(e.resonance_db) + "  # sensor units per unit of output\n";
  out += "usable_band_hz = [" + exact_number(e.band_low_hz) + ", " + exact_number(e.band_high_hz) + "]\n";
  out += "delay_ms = " + exact_number(e.delay_ms) + "  # the chain's pure delay (the sound card's round trip included)\n";
  if (e.round_trip_ms)
    out += "round_trip_ms = " + exact_number(*e.round_trip_ms) + "  # the sound card's, measured by a loopback cable\n";
  out += "gain_limit_db = " + exact_number(e.gain_limit_db) + "\n";
  out += "target_db = " + exact_number(e.target_db) + "  # the level the chain is equalised to\n";
  out += "latency_samples = " + exact_number(e.latency_samples) + "  # the inverse's group delay over the band\n";
  out += "\n[response]  # 1/12 octave over the sweep\n";
  out += "frequency_hz = " + list(e.frequency_hz, 6) + "\n";
  out += "magnitude_db = " + list(e.magnitude_db, 6) + "\n";
  out += "phase_deg = " + list(e.phase_deg, 6) + "\n";
  out += "\n[inverse]  # the minimum-phase FIR filter, y[n] = sum taps[j] * x[n - j]\n";
  out += "taps = " + list(e.taps, 4) + "\n";
  return out;
}

void write_actuator_eq_file(const std::filesystem::path& path, const ActuatorEq& eq) {
  if (const auto p = problem_of(eq))
    throw std::invalid_argument(path.string() + ": refusing to write an actuator calibration whose " + p->first + " " + p->second);
  write_file_atomically(path, format_actuator_eq(eq));
}

}  // namespace mallet
