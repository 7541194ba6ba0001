#pragma once
// `mallet calibrate latency --loopback CH`: the sound card's round trip measured on a cable
// from the actuator's output to input channel CH, and from it the output latency that
// [timing] audio_output_latency_ms stands for (the round trip less the input latency
// PortAudio reports for the same stream). A short exponential sweep, 50 Hz to 15 kHz, after
// 0.25 s of silence; the delay is the peak of the cable's deconvolved response, interpolated.
//
// What was measured is kept in the state folder (latency.toml: when, the round trip, both
// latencies and the devices), so that `mallet doctor` can say when it was last measured.
#include <filesystem>
#include <optional>
#include <string>

#include "audio/duplex_measurement.hpp"

namespace mallet::app {

struct LatencyMeasurement {
  std::string measured_utc;
  int sample_rate_hz = 0;
  double round_trip_samples = 0;
  double portaudio_input_latency_ms = 0;   //!< as PortAudio reports the stream's
  double portaudio_output_latency_ms = 0;
  std::string output_device, input_device;
  unsigned long xruns = 0;

  double round_trip_ms() const { return 1000.0 * round_trip_samples / sample_rate_hz; }
  //! The round trip less PortAudio's input latency: what audio_output_latency_ms means.
  double output_latency_ms() const { return round_trip_ms() - portaudio_input_latency_ms; }
};

//! `io.output_channel` plays (the actuator's), `loopback_channel` (0-based) records. Throws
//! MeasurementRefused (recording_checks.hpp) for a loopback that clips or carries nothing.
LatencyMeasurement measure_round_trip(audio::DuplexRequest io, int loopback_channel);

//! latency.toml's text, and the file read back (none when absent; a FileError when malformed).
std::string format_latency_record(const LatencyMeasurement& m);
std::optional<LatencyMeasurement> load_latency_record(const std::filesystem::path& path);

}  // namespace mallet::app
