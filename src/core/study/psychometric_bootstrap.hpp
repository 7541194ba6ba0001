#pragma once
// How sure a psychometric fit is: 95 % confidence intervals for its threshold, slope and
// (when fitted) lapse by the parametric bootstrap (Wichmann & Hill 2001, "The psychometric
// function: II. Bootstrap-based confidence intervals and sampling"), and the fit's goodness
// by the same resamples. Each resample draws every level's correct answers anew from the
// fitted curve, Binomial(trials, P(x)), and is fitted again by the fit's own climb, to the
// same precision (psychometric_fit.hpp); a resample with the data's own counts is the fit
// itself. The interval runs between the refits' bias-corrected 2.5th and 97.5th percentiles
// (Efron 1987: moved by how far the refits' median lies from the fit, refits equal to the
// fit counting half below it). The draws come from one seeded generator (the study's
// SplitMix64, each answer a uniform < P): the same intervals on every machine.
//
// The refits live in the fit's box, so an interval never leaves what the quantity can be: a
// threshold's never goes below 0. Where it reaches a side of the box that is only the end of
// the search (one span beyond the tested differences, or the slope's bounds), that end is
// not a limit and the interval is one-sided ("≤ 13.4"): `lo_open`/`hi_open`. A step's refits
// are all much the same step, so its threshold's interval also holds the likelihood-ratio
// 95 % limits of where the step may stand (psychometric_fit.hpp).
//
// Goodness of fit (Wichmann & Hill 2001, part I): the share of resamples whose deviance
// against their own refit is at least the data's deviance, its p-value.
#include <cstdint>
#include <string>
#include <vector>

#include "core/study/psychometric_fit.hpp"

namespace mallet::study {

struct Interval {
  double lo = 0, hi = 0;
  bool lo_open = false, hi_open = false;  //!< that end is the search's edge: no limit there
  bool contains(double v) const { return (lo_open || lo <= v) && (hi_open || v <= hi); }
};

struct PsychometricIntervals {
  bool ok = false;
  Interval threshold, slope, lapse;  //!< 95 %, bias-corrected percentiles (lapse: when fitted)
  int resamples = 0;                 //!< refits made
  int extrapolated = 0;              //!< of those, thresholds beyond the tested range (a caveat)
  double deviance_p = 1;             //!< share of resamples' deviances ≥ the fit's
};

inline constexpr int kDefaultResamples = 1000;

//! Intervals for `fit` (which must have a threshold) of `levels` under `options`;
//! `resamples` ≥ 20.
PsychometricIntervals bootstrap_fit(const std::vector<PsychometricLevel>& levels, const FitOptions& options,
                                    const PsychometricFit& fit, int resamples, std::uint64_t seed);

//! The default fit's (2AFC logistic, 75 %, no lapse).
inline PsychometricIntervals bootstrap_2afc(const std::vector<PsychometricLevel>& levels, const PsychometricFit& fit,
                                            int resamples, std::uint64_t seed) {
  return bootstrap_fit(levels, {}, fit, resamples, seed);
}

}  // namespace mallet::study
