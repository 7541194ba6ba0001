#include "app/calibration/latency_calibration.hpp"

#include <fmt/format.h>

#include "app/calibration/recording_checks.hpp"
#include "audio/actuator_response.hpp"
#include "audio/exp_sweep.hpp"
#include "core/calibration_file.hpp"

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
  io.input_channels = {loopback_channel};
  io.tail_s = 0.5;
  const audio::DuplexRecording rec = record_whole(io, after_silence(sweep, lead));
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

}  // namespace mallet::app
