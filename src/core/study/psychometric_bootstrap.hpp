#pragma once
// How sure a psychometric fit is: 95 % confidence intervals for its threshold and slope by
// the parametric bootstrap (Wichmann & Hill 2001, "The psychometric function: II.
// Bootstrap-based confidence intervals and sampling"). Each resample draws every level's
// correct answers anew from the fitted function, Binomial(trials, P(x)), and is fitted
// again; the interval runs between the refits' bias-corrected 2.5th and 97.5th percentiles
// (Efron 1987: moved by how far the refits' median lies from the fit). The draws come from
// one seeded generator (the study's SplitMix64, each answer a uniform < P): the same
// intervals on every machine for the same data and seed.
#include <cstdint>
#include <string>
#include <vector>

#include "core/study/psychometric_fit.hpp"

namespace mallet::study {

struct Interval {
  double lo = 0, hi = 0;
  bool contains(double v) const { return lo <= v && v <= hi; }
};

struct PsychometricIntervals {
  bool ok = false;
  Interval threshold, slope;  //!< 95 %, bias-corrected percentiles
  int resamples = 0;          //!< refits that gave a fit
  int extrapolated = 0;       //!< of those, thresholds beyond the tested range (a caveat)
};

inline constexpr int kDefaultResamples = 1000;

//! Intervals for `fit` (which must be ok) of `levels`; `resamples` ≥ 20.
PsychometricIntervals bootstrap_2afc(const std::vector<PsychometricLevel>& levels, const PsychometricFit& fit,
                                     int resamples, std::uint64_t seed);

}  // namespace mallet::study
