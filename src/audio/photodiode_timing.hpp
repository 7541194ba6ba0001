#pragma once
// The display's latency from a photodiode's recording: how long after a frame's present
// (the kiosk's PresentClock) its light reached the photodiode on the screen's corner.
//
// The recording is the kiosk's own output stream's (audio/stream_capture.hpp), so its
// samples have a time on the kiosk's clock. A host buffer's first callback runs once the
// buffer is due, never early (later ones of the same buffer, when PortAudio splits it into
// smaller blocks, run at once after it and are left out). So the earliest of those
// callbacks' times less their frames' place, over the host buffer holding a sample and the
// half second after it, is when the recording's first frame was due on the schedule the
// sample is on (a host can skip time: never the buffers before), and the sample reached the
// input that long before its place by PortAudio's input latency:
//
//     light(n) = min over host buffers from n's on (callback − place) + n / rate − input latency
//
// For each square the page showed, the light's onset is the first crossing of half the
// largest swing from the 300 ms before the square's present (so a photodiode wired either
// way round, or AC-coupled by the line input, reads the same), interpolated between
// samples, looked for from 5 ms before the present to 300 ms after. The display latency is
// the median over the squares seen, against the present of the first frame that showed each.
#include <optional>
#include <string>
#include <vector>

#include "audio/stream_capture.hpp"
#include "core/time.hpp"

namespace mallet::audio {

struct PhotodiodeSquare {
  Nanos instant = 0;  //!< when the test scheduled it (its note heard then)
  Nanos present = 0;  //!< the present of the first frame that showed it; 0: never shown
};

struct PhotodiodePulse {
  Nanos present = 0;
  std::optional<Nanos> light;       //!< the onset, on the kiosk's clock; none: not seen
  std::optional<double> latency_ms; //!< light − present
};

struct PhotodiodeTiming {
  std::vector<PhotodiodePulse> pulses;  //!< one per square, in order
  int seen = 0;
  double display_latency_ms = 0;  //!< the median of the latencies seen
  double min_ms = 0, max_ms = 0;
  double noise_to_swing = 0;      //!< the worst seen square's: the 300 ms before, rms, over its swing
  int near_xruns = 0;             //!< squares left out: the stream over- or underran near them
};

//! Times each square's light in channel `channel` of `recording`, leaving out a square near an
//! over- or underrun. Throws std::runtime_error with one line (naming input channel
//! `channel_label`) when the recording skipped frames or fewer than half of the squares show
//! a swing ten times the noise before it.
PhotodiodeTiming time_photodiode(const CaptureRecording& recording, std::size_t channel,
                                 double input_latency_s, const std::vector<PhotodiodeSquare>& squares,
                                 const std::string& channel_label);

//! The recording's sample `n` on the kiosk's clock (the formula above, before the input latency).
Nanos capture_time(const CaptureRecording& recording, double n);

}  // namespace mallet::audio
