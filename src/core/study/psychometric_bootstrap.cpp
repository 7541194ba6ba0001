#include "core/study/psychometric_bootstrap.hpp"

#include <algorithm>
#include <cmath>

#include "core/study/balanced_schedule.hpp"

namespace mallet::study {

namespace {

//! The q-quantile of sorted values, linearly interpolated between order statistics.
double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(at));
  const std::size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (sorted[j] - sorted[i]) * (at - static_cast<double>(i));
}

//! The bias-corrected percentile interval (Efron 1987): the percentiles moved by how far the
//! refits' median lies from the estimate, z0 = Φ⁻¹(share of refits below it, those equal to it
//! counting half). Plain percentiles of a skewed bootstrap distribution miss the true value on
//! one side more often. `lo_edge`/`hi_edge`: the search's ends, not limits (open there).
Interval bias_corrected(std::vector<double>& refits, double estimate, double lo_edge, double hi_edge) {
  std::sort(refits.begin(), refits.end());
  const auto below = std::lower_bound(refits.begin(), refits.end(), estimate) - refits.begin();
  const auto up_to = std::upper_bound(refits.begin(), refits.end(), estimate) - refits.begin();
  const double n = static_cast<double>(refits.size());
  const double share = std::clamp((static_cast<double>(below) + 0.5 * static_cast<double>(up_to - below)) / n,
                                  1.0 / (n + 1), n / (n + 1));
  const double z0 = normal_quantile(share), z = normal_quantile(0.975);
  Interval i{quantile(refits, normal_cdf(2 * z0 - z)), quantile(refits, normal_cdf(2 * z0 + z))};
  i.lo = std::min(i.lo, estimate);  // an interval always holds its own estimate
  i.hi = std::max(i.hi, estimate);
  const double touch = 1e-6 * (hi_edge - lo_edge);
  i.lo_open = i.lo <= lo_edge + touch;
  i.hi_open = i.hi >= hi_edge - touch;
  return i;
}

bool same_counts(const std::vector<PsychometricLevel>& a, const std::vector<PsychometricLevel>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].correct != b[i].correct) return false;
  return true;
}

}  // namespace

PsychometricIntervals bootstrap_fit(const std::vector<PsychometricLevel>& input, const FitOptions& options,
                                    const PsychometricFit& fit, int resamples, std::uint64_t seed) {
  PsychometricIntervals out;
  if (!fit.has_threshold() || resamples < 20) return out;
  const std::vector<PsychometricLevel> levels = merged_levels(input);
  SplitMix64 rng(seed);  // the study's own generator: the same draws on every machine
  std::vector<double> thresholds, slopes, lapses;
  int deviance_at_least = 0;
  std::vector<PsychometricLevel> drawn = levels;
  const PsychometricParams curve{fit.threshold, fit.slope, fit.lapse};
  const double middle = (levels.front().x + levels.back().x) / 2;
  for (int r = 0; r < resamples; ++r) {
    for (PsychometricLevel& l : drawn) {
      const double p = psychometric_p(options.model, curve, l.x);
      l.correct = 0;
      for (int k = 0; k < l.trials; ++k) l.correct += rng.unit() < p;
    }
    const PsychometricFit refit = same_counts(drawn, levels) ? fit : refit_psychometric(drawn, options, fit);
    if (!refit.ok) continue;
    // A refit without a rise has no threshold; it counts as beyond whichever end its level
    // accuracy lies: below the criterion, above the range; at or over it, below.
    double threshold = refit.threshold;
    if (refit.flat)
      threshold = psychometric_p(options.model, {refit.threshold, refit.slope, refit.lapse}, middle) <
                          options.model.criterion
                      ? fit.box.threshold_hi
                      : fit.box.threshold_lo;
    thresholds.push_back(threshold);
    slopes.push_back(refit.slope);
    lapses.push_back(refit.lapse);
    if (refit.extrapolated) ++out.extrapolated;
    if (refit.deviance >= fit.deviance) ++deviance_at_least;
  }
  out.resamples = static_cast<int>(thresholds.size());
  if (out.resamples < 20) return out;
  const FitBox& box = fit.box;
  out.threshold = bias_corrected(thresholds, fit.threshold, box.threshold_lo, box.threshold_hi);
  if (fit.step) {
    // Every refit of a step is much the same step: the likelihood says where it may stand.
    out.threshold.lo = std::min(out.threshold.lo, fit.step_threshold_lo);
    out.threshold.hi = std::max(out.threshold.hi, fit.step_threshold_hi);
    const double touch = 1e-6 * (box.threshold_hi - box.threshold_lo);
    out.threshold.lo_open = out.threshold.lo <= box.threshold_lo + touch;
    out.threshold.hi_open = out.threshold.hi >= box.threshold_hi - touch;
  }
  if (box.threshold_lo_is_zero) out.threshold.lo_open = false;  // 0 is a limit: the least a difference can be
  out.slope = bias_corrected(slopes, fit.slope, box.slope_lo, box.slope_hi);
  if (options.fit_lapse) {
    out.lapse = bias_corrected(lapses, fit.lapse, box.lapse_lo, box.lapse_hi);
    out.lapse.lo_open = out.lapse.hi_open = false;  // 0 and the limit are what a lapse rate may be
  }
  out.deviance_p = static_cast<double>(deviance_at_least) / out.resamples;
  out.ok = true;
  return out;
}

}  // namespace mallet::study
