#include "core/display_latency_record.hpp"

#include <fmt/format.h>

#include "core/config/toml_reader.hpp"
#include "core/toml_text.hpp"

namespace mallet {

std::string format_display_latency(const DisplayLatencyMeasurement& m) {
  using toml_text::exact_number;
  std::string out = "# Mallet: the display's latency as `mallet calibrate latency --photodiode` measured it.\n";
  out += "format_version = 1\n";
  out += "measured_utc = " + toml_text::quoted(m.measured_utc) + "\n";
  out += "display_latency_ms = " + exact_number(m.display_latency_ms) +
         "  # from a frame's present to light on the panel: the median\n";
  out += "min_ms = " + exact_number(m.min_ms) + "\n";
  out += "max_ms = " + exact_number(m.max_ms) + "\n";
  out += fmt::format("squares_seen = {}\nsquares = {}\n", m.squares_seen, m.squares);
  out += "input_device = " + toml_text::quoted(m.input_device) + "\n";
  out += fmt::format("photodiode_channel = {}  # from 1\n", m.photodiode_channel);
  out += fmt::format("saved = {}  # the operator confirmed it as [timing] display_latency_ms\n", m.saved);
  return out;
}

std::optional<DisplayLatencyMeasurement> load_display_latency(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  const toml::table root = config::parse_file(path);
  config::TableReader t(root, path.string());
  if (t.integer("format_version") != 1) t.fail("format_version", "this mallet reads format_version = 1");
  DisplayLatencyMeasurement m;
  m.measured_utc = t.string("measured_utc");
  m.display_latency_ms = t.number("display_latency_ms");
  if (!(m.display_latency_ms >= 0 && m.display_latency_ms <= 200)) t.fail("display_latency_ms", "must be 0 to 200");
  m.min_ms = t.number("min_ms");
  m.max_ms = t.number("max_ms");
  m.squares_seen = static_cast<int>(t.integer("squares_seen"));
  m.squares = static_cast<int>(t.integer("squares"));
  if (m.squares < 1 || m.squares_seen < 1 || m.squares_seen > m.squares)
    t.fail("squares_seen", "must be 1 to squares");
  m.input_device = t.string_or("input_device", "");
  m.photodiode_channel = static_cast<int>(t.integer("photodiode_channel"));
  if (m.photodiode_channel < 1) t.fail("photodiode_channel", "counts from 1");
  m.saved = t.boolean_or("saved", false);
  t.finish();
  return m;
}

}  // namespace mallet
