#pragma once
// `mallet bench input`'s measures of a 1€ filter setting on the workload: the still cursor's
// jitter, the lag in fast (strikes) and slow (aiming) motion, and the strikes the contact
// solver then finds, each matched to its true strike.
#include <vector>

#include "app/bench/bench_input_workload.hpp"
#include "core/one_euro_filter.hpp"
#include "core/scene.hpp"

namespace mallet::app::input_bench {

struct ImpactScore {
  double speed_bias_pct = 0, speed_abs_pct = 0, time_mean_ms = 0, time_max_abs_ms = 0;
  int matched = 0, missed = 0, extra = 0;
};

struct Found {
  Nanos t;
  int target;
  double speed;
};

//! Matches each true strike to the found impact on the same bar nearest in time (±60 ms).
ImpactScore score(const std::vector<StrikeTrack>& tracks, const std::vector<std::vector<Found>>& found);

struct Result {
  OneEuroConfig cfg;
  double jitter_mm = 0;
  double lag_ms = 0;       //!< strikes: while the hand moves > 0.3 m/s
  double slow_lag_ms = 0;  //!< a slowly circling hand (≈5 cm/s): aiming
  ImpactScore segments;    //!< Mallet fed the filtered positions
  ImpactScore derivative;  //!< same impacts, speed from the filter's derivative
};

//! Per-axis standard deviation of the still cursor (after 1 s to settle), mm.
double jitter_mm(const std::vector<Observed>& still, const OneEuroConfig* cfg);

//! The time shift (ms) that best aligns the filtered track with the truth while the hand
//! moves faster than 0.3 m/s: argmin over τ of mean |f(t) − truth(t − τ)|², searched in
//! 1 ms steps over −10..150 ms, then in 0.05 ms steps around the best.
double lag_ms(const std::vector<StrikeTrack>& tracks, const std::vector<std::vector<Vec2>>& filtered);

//! Each track's raw positions through a fresh filter set to `cfg`.
std::vector<std::vector<Vec2>> filter_tracks(const std::vector<StrikeTrack>& tracks, const OneEuroConfig& cfg);

//! One setting measured: jitter, both lags, and the impacts from its segments and from its derivative.
Result evaluate(const Scene& scene, const std::vector<Observed>& still, const std::vector<StrikeTrack>& slow,
                const std::vector<StrikeTrack>& tracks, const OneEuroConfig& cfg);

//! The filter's impacts per speed track (Mallet fed the filtered positions).
std::vector<std::vector<Found>> filtered_impacts(const Scene& scene, const std::vector<StrikeTrack>& tracks,
                                                 const OneEuroConfig* cfg);

}  // namespace mallet::app::input_bench
