#pragma once
// What `mallet calibrate latency --loopback` measured of the sound card, kept in the state
// folder (latency.toml) so that `mallet doctor` can say when the latency was last measured:
//
//   format_version = 1
//   measured_utc = "2026-12-06T09:30:00Z"
//   sample_rate_hz = 48000
//   round_trip_ms = 10.333                # output to input, on the loopback cable
//   output_latency_ms = 10.333            # the round trip less PortAudio's input latency
//   portaudio_input_latency_ms = 0.0
//   portaudio_output_latency_ms = 5.333
//   output_device = "system"
//   input_device = "system"
#include <filesystem>
#include <optional>
#include <string>

namespace mallet {

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

//! latency.toml's text, and the file read back (none when absent; a FileError naming the
//! file, the place and the key when malformed).
std::string format_latency_record(const LatencyMeasurement& m);
std::optional<LatencyMeasurement> load_latency_record(const std::filesystem::path& path);

}  // namespace mallet
