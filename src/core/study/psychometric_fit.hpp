#pragma once
// A psychometric function for a 2AFC task, fitted by maximum likelihood:
//     P(correct | x) = 0.5 + 0.5 / (1 + e^(−slope·(x − threshold)))
// x is the stimulus difference (percent difference in Eq. 1's B for study mode); guessing
// gives 0.5, so `threshold` is the difference answered correctly 75 % of the time and
// `slope` how fast accuracy rises there (dP/dx = slope/8 at the threshold). The binomial
// likelihood is maximised over a bounded grid refined five times: no derivative, no start
// value to choose, the same answer on every machine.
#include <cmath>
#include <string>
#include <vector>

namespace mallet::study {

struct PsychometricLevel {
  double x = 0;
  int trials = 0;
  int correct = 0;
};

struct PsychometricFit {
  bool ok = false;
  std::string reason;  //!< why there is no fit, or a caveat ("threshold beyond the tested range")
  double threshold = 0;
  double slope = 0;
  double log_likelihood = 0;
  int levels = 0;
};

inline double psychometric_2afc(double x, double threshold, double slope) {
  return 0.5 + 0.5 / (1.0 + std::exp(-slope * (x - threshold)));
}

//! The grid searched: `points` × `points` (threshold × log slope) per round, each round
//! zoomed to ±4 steps around the best. The default ends at a step of about 1e-7 of the
//! searched range; the bootstrap's refits (psychometric_bootstrap.hpp) end at under 1e-5 of
//! it, far below any interval's width, for a seventh of the likelihoods.
struct FitGrid {
  int points = 81;
  int rounds = 6;
};
inline constexpr FitGrid kBootstrapGrid{25, 9};

//! Needs at least 3 distinct x with trials; otherwise ok = false and reason says so.
PsychometricFit fit_psychometric_2afc(const std::vector<PsychometricLevel>& levels, FitGrid grid = {});

//! The same maximum found by Newton's method from `near` (a fit of similar data: the
//! bootstrap's resamples), to 1e-7 of the tested range; ok = false when it does not settle on
//! a maximum inside the grid's bounds (a step-like or flat resample), for the grid to decide.
PsychometricFit refit_psychometric_2afc(const std::vector<PsychometricLevel>& levels, const PsychometricFit& near);

}  // namespace mallet::study
