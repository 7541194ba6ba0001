#include "core/latency_record.hpp"

#include <fmt/format.h>

#include "core/config/toml_reader.hpp"
#include "core/toml_text.hpp"

namespace mallet {

std::string format_latency_record(const LatencyMeasurement& m) {
  using toml_text::exact_number;
  std::string out = "# Mallet: the sound card's latency as `mallet calibrate latency --loopback` measured it.\n";
  out += "format_version = 1\n";
  out += "measured_utc = " + toml_text::quoted(m.measured_utc) + "\n";
  out += fmt::format("sample_rate_hz = {}\n", m.sample_rate_hz);
  out += "round_trip_ms = " + exact_number(m.round_trip_ms()) + "  # output to input, on the loopback cable\n";
  out += "output_latency_ms = " + exact_number(m.output_latency_ms()) + "  # the round trip less PortAudio's input latency\n";
  out += "portaudio_input_latency_ms = " + exact_number(m.portaudio_input_latency_ms) + "\n";
  out += "portaudio_output_latency_ms = " + exact_number(m.portaudio_output_latency_ms) + "\n";
  out += "output_device = " + toml_text::quoted(m.output_device) + "\n";
  out += "input_device = " + toml_text::quoted(m.input_device) + "\n";
  return out;
}

std::optional<LatencyMeasurement> load_latency_record(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  const toml::table root = config::parse_file(path);
  config::TableReader t(root, path.string());
  if (t.integer("format_version") != 1) t.fail("format_version", "this mallet reads format_version = 1");
  LatencyMeasurement m;
  m.measured_utc = t.string("measured_utc");
  m.sample_rate_hz = static_cast<int>(t.integer("sample_rate_hz"));
  if (m.sample_rate_hz < 8000 || m.sample_rate_hz > 384000) t.fail("sample_rate_hz", "must be 8000 to 384000");
  m.round_trip_samples = t.number("round_trip_ms") * m.sample_rate_hz / 1000.0;
  (void)t.number("output_latency_ms");  // derived: read for the check of unknown keys only
  m.portaudio_input_latency_ms = t.number("portaudio_input_latency_ms");
  m.portaudio_output_latency_ms = t.number("portaudio_output_latency_ms");
  m.output_device = t.string_or("output_device", "");
  m.input_device = t.string_or("input_device", "");
  t.finish();
  return m;
}

}  // namespace mallet
