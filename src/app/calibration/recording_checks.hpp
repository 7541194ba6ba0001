#pragma once
// What every measurement through the sound card checks of its recording before using it
// (`mallet calibrate actuator`, `mallet calibrate latency`): a channel that clips or holds
// nothing but noise is refused with one line saying what to do (MeasurementRefused: exit 2),
// and a recording during which the stream over- or underran is made again.
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "audio/duplex_measurement.hpp"

namespace mallet::app {

//! The recording is not fit to measure with: what to do about it, in one line (exit 2).
class MeasurementRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr double kClipLevel = 0.99;  //!< |x| at or above it: the input clipped
inline constexpr double kMinSnrDb = 20.0;   //!< the signal's RMS over the noise's before it

struct ChannelLevels {
  double peak_dbfs = 0;
  double snr_db = 0;  //!< 200 when the noise before the signal was exactly zero
};

//! `x`: `lead` samples of silence, then `played` samples of the signal. Throws
//! MeasurementRefused naming `what` ("the sensor (input channel 1)") when it clips or records
//! silence (less than kMinSnrDb over the noise).
ChannelLevels check_channel(std::span<const double> x, std::size_t lead, std::size_t played, const std::string& what);

//! What the stream plays: `lead` samples of silence (the noise floor check_channel measures),
//! then `signal`.
std::vector<float> after_silence(std::span<const double> signal, std::size_t lead);

//! play_and_record, made again (three times in all) while the stream over- or underran; the
//! last recording is kept, its xruns counted in it. An input that records nothing
//! (audio::NoInput) is a MeasurementRefused with the same line.
audio::DuplexRecording record_whole(const audio::DuplexRequest& io, std::span<const float> signal);

//! Says the refusal on stderr in one line ("mallet: ...") and ends the command with status 2.
[[noreturn]] void refuse_measurement(const MeasurementRefused& refused);

}  // namespace mallet::app
