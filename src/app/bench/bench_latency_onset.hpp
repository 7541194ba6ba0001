#pragma once
// Where a strike begins in a recorded channel, for `mallet bench latency`.
//
// Strokes come every 600 ms, and the glockenspiel rings for seconds (its fundamental
// decays at 2.3/s): the note channel is rarely silent when the next strike starts, and a
// quiet strike on the xylophone can be softer than the ring it starts over. "The first
// non-zero sample after silence" finds nothing there, and a level threshold finds it late.
// What does work: a ringing bar is a sum of damped sinusoids, which a linear predictor
// fitted on the samples just before continues exactly (x[n] = Σ a_k x[n−k] holds for every
// n while no voice starts or stops). A new strike is the first sample the predictor does
// not explain. Over silence it is the first non-zero sample.
#include <cstddef>
#include <optional>
#include <vector>

namespace mallet::app::latency {

struct OnsetSearch {
  int order = 32;              //!< predictor order: 2 per sinusoid ringing, with room to spare
  std::size_t training = 960;  //!< samples before `from` the predictor is fitted on (20 ms at 48 kHz)
  double silence = 1e-6;       //!< a training window quieter than this is silence
  //! A residual above max(floor, factor × the training residual's RMS) is a new strike.
  //! The floor sits above the step a voice makes when the engine retires it (envelope
  //! < 1e-5) and far below a strike's first sample (≥ 1e-3 at the slowest strokes).
  double floor = 3e-5;
  double factor = 30.0;
};

//! A stretch of samples that may not continue the ones before it (a JACK cycle that came
//! late: the kiosk's stream may have skipped there), as [begin, end).
struct Gap {
  std::size_t begin = 0, end = 0;
};

//! The first sample in [from, to) that starts something new, or nothing. A candidate inside
//! one of `gaps` (sorted) is a seam, not a strike: the search goes on `order` samples after
//! the gap, when the predictor has clean history again.
std::optional<std::size_t> find_onset(const std::vector<float>& x, std::size_t from, std::size_t to,
                                      const OnsetSearch& search = {}, const std::vector<Gap>& gaps = {});

}  // namespace mallet::app::latency
