#include "app/calibration/latency_calibration.hpp"

#include <fmt/format.h>

#include "app/calibration/recording_checks.hpp"
#include "audio/actuator_response.hpp"
#include "audio/exp_sweep.hpp"
#include "core/calibration_file.hpp"
#include "core/config/toml_reader.hpp"
#include "core/toml_text.hpp"

namespace mallet::app {

LatencyMeasurement measure_round_trip(audio::DuplexRequest io, int loopback_channel) {
  audio::SweepSpec spec;
  spec.f1_hz = 50;
  spec.f2_hz = 15000;
  spec.duration_s = 1.0;
  spec.fade_s = 0.005;
  spec.sample_rate_hz = io.sample_rate_hz;
  const std::vector<double> sweep = audio::exp_sweep(spec);
  const auto lead = static_cast<std::size_t>(0.25 * io.sample_rate_hz);
  std::vector<float> played(lead + sweep.size(), 0.0f);
  for (std::size_t i = 0; i < sweep.size(); ++i) played[lead + i] = static_cast<float>(sweep[i]);
  io.input_channels = {loopback_channel};
  io.tail_s = 0.5;
  const audio::DuplexRecording rec = record_whole(io, played);
  check_channel(rec.channels[0], lead, sweep.size(), fmt::format("loopback (input channel {})", loopback_channel + 1));
  const std::vector<double> h = audio::deconvolve_sweep(std::span<const double>(rec.channels[0]).subspan(lead), sweep,
                                                        spec, audio::kDeconvolutionPre + 16384);
  LatencyMeasurement m;
  m.measured_utc = utc_timestamp_now();
  m.sample_rate_hz = io.sample_rate_hz;
  m.round_trip_samples = audio::flat_path_delay(h, audio::kDeconvolutionPre);
  m.portaudio_input_latency_ms = 1000.0 * rec.input_latency_s;
  m.portaudio_output_latency_ms = 1000.0 * rec.output_latency_s;
  m.output_device = rec.output_name;
  m.input_device = rec.input_name;
  m.xruns = rec.xruns;
  return m;
}

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

}  // namespace mallet::app
