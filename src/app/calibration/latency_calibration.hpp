#pragma once
// `mallet calibrate latency --loopback CH`: the sound card's round trip measured on a cable
// from the actuator's output to input channel CH, and from it the output latency that
// [timing] audio_output_latency_ms stands for (the round trip less the input latency
// PortAudio reports for the same stream). A short exponential sweep, 50 Hz to 15 kHz, after
// 0.25 s of silence; the delay is the peak of the cable's deconvolved response, interpolated.
//
// What was measured is kept in the state folder (latency.toml: when, the round trip, both
// latencies and the devices), so that `mallet doctor` can say when it was last measured.
#include "audio/duplex_measurement.hpp"
#include "core/latency_record.hpp"

namespace mallet::app {

//! `io.output_channel` plays (the actuator's), `loopback_channel` (0-based) records. Throws
//! MeasurementRefused (recording_checks.hpp) for a loopback that clips or carries nothing.
LatencyMeasurement measure_round_trip(audio::DuplexRequest io, int loopback_channel);

}  // namespace mallet::app
