#pragma once
// A psychometric function fitted by maximum likelihood to a forced-choice task's answers:
//     P(correct | x) = γ + (1 − γ − λ)·F(x)        (psychometric_shape.hpp)
// x is the stimulus difference (percent difference in Eq. 1's B for study mode), γ = 0.5 for
// 2AFC, F one of four shapes in threshold and slope, λ the lapse rate, fixed or fitted
// within [0, lapse_limit] (Wichmann & Hill 2001 bound it at 0.06).
//
// Where the maximum is. The parameters are searched in a box: the threshold within one span
// of the tested differences (never below 0 when every difference is ≥ 0: at 0 the two taps
// are the same and only guessing is left), the slope from "accuracy barely changes over 100
// spans" to "it jumps within a hundredth of one". A coarse grid over the whole box finds the
// basin, and a projected Newton's method climbs to the maximum to 1e-10 of the box, also
// when the maximum lies on a side of the box (a step, or a threshold beyond the range). The
// bootstrap's refits use the same climb to the same precision (psychometric_bootstrap.hpp).
//
// What the maximum means. A maximum on a side of the box is not an estimate, and is reported
// as what it says about the data:
//   threshold at the box's low side   "threshold below the tested range": no number;
//   threshold at the box's high side  "threshold above the tested range": no number;
//   slope at its upper bound          "a step": the threshold is where the step is, and the
//                                     slope is only known to be at least `slope_at_least`
//                                     (the likelihood-ratio 95 % limit);
//   slope at its lower bound          "no rise": accuracy does not change; no threshold;
//   a step beyond the tested range    as likely anywhere out there: "threshold below/above".
#include <cmath>
#include <string>
#include <vector>

#include "core/study/psychometric_shape.hpp"

namespace mallet::study {

struct PsychometricLevel {
  double x = 0;
  int trials = 0;
  int correct = 0;
};

//! Mallet's first fit, kept for the simulated observer: the 2AFC logistic at 75 %, no lapse.
inline double psychometric_2afc(double x, double threshold, double slope) {
  return 0.5 + 0.5 / (1.0 + std::exp(-slope * (x - threshold)));
}

//! What is fitted: the curve's form, and the lapse rate fixed (at `lapse`) or fitted (within
//! [0, lapse_limit]).
struct FitOptions {
  PsychometricModel model;
  bool fit_lapse = false;
  double lapse = 0;           //!< λ when fixed
  double lapse_limit = 0.06;  //!< λ's upper bound when fitted
};

//! The box searched, from the levels tested (see the top of this file).
struct FitBox {
  double threshold_lo = 0, threshold_hi = 0;
  double slope_lo = 0, slope_hi = 0;
  double lapse_lo = 0, lapse_hi = 0;
  bool threshold_lo_is_zero = false;  //!< the low side is 0 (a difference cannot be less), not the range's edge
};

struct PsychometricFit {
  bool ok = false;      //!< a maximum was found (enough levels)
  std::string reason;   //!< why there is no fit, or what its maximum means ("a step: …")
  double threshold = 0;
  double slope = 0;
  double lapse = 0;
  double log_likelihood = 0;
  int levels = 0;
  FitBox box;
  // Where the maximum lies (above): each is also said in `reason`.
  bool threshold_below = false, threshold_above = false;  //!< on the box's side: no estimate
  bool extrapolated = false;   //!< inside the box but outside the tested differences
  bool step = false;           //!< slope at its upper bound
  bool flat = false;           //!< slope at its lower bound: no rise, no threshold
  bool lapse_at_limit = false; //!< fitted λ at lapse_limit
  double slope_at_least = 0;   //!< a step: the slope's likelihood-ratio 95 % lower limit
  //! A step: the thresholds within the likelihood-ratio 95 % limits (where the step may stand).
  double step_threshold_lo = 0, step_threshold_hi = 0;
  //! The threshold is an estimate: a maximum inside the box's threshold range, on a rise.
  bool has_threshold() const { return ok && !threshold_below && !threshold_above && !flat; }
  //! The slope is an estimate: neither a step nor flat.
  bool has_slope() const { return has_threshold() && !step; }
  //! Goodness of fit: the deviance (twice the log-likelihood ratio of the saturated model),
  //! and each level's deviance residual (signed: above the curve is positive), ascending x.
  double deviance = 0;
  std::vector<double> residuals;
};

//! Needs at least 3 distinct x with trials; otherwise ok = false and reason says so.
PsychometricFit fit_psychometric(const std::vector<PsychometricLevel>& levels, const FitOptions& options = {});

//! The same maximum, climbed to from `near` (the fit of the data a bootstrap resample was
//! drawn from) with the same Newton's method and precision; where the climb ends on a side of
//! the box or not at a maximum, and always with a fitted lapse (whose likelihood can have a
//! second summit), the whole search of fit_psychometric decides. It skips what only a
//! reported fit needs: a step's likelihood-ratio limits.
PsychometricFit refit_psychometric(const std::vector<PsychometricLevel>& levels, const FitOptions& options,
                                   const PsychometricFit& near);

//! The default fit (2AFC logistic, 75 %, no lapse): Mallet's first, kept for its callers.
inline PsychometricFit fit_psychometric_2afc(const std::vector<PsychometricLevel>& levels) {
  return fit_psychometric(levels, {});
}

//! The log-likelihood of `levels` under the curve (probabilities kept within 1e-12 of 0 and 1).
double psychometric_log_likelihood(const std::vector<PsychometricLevel>& levels, const PsychometricModel& model,
                                   const PsychometricParams& params);

//! The levels merged by x (trials and correct answers added), ascending x; no empty or
//! non-finite levels.
std::vector<PsychometricLevel> merged_levels(const std::vector<PsychometricLevel>& input);

}  // namespace mallet::study
