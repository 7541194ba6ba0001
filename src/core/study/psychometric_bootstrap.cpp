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

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

//! Φ⁻¹(p) by bisection on Φ (a handful of calls per summary: exactness over speed).
double normal_quantile(double p) {
  double lo = -40, hi = 40;
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = (lo + hi) / 2;
    (normal_cdf(mid) < p ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

//! The bias-corrected percentile interval (Efron 1987): the percentiles moved by how far the
//! refits' median lies from the estimate, z0 = Φ⁻¹(share of refits below it). Plain
//! percentiles of a skewed bootstrap distribution miss the true value on one side more often.
Interval bias_corrected(std::vector<double>& refits, double estimate) {
  std::sort(refits.begin(), refits.end());
  const auto below = std::lower_bound(refits.begin(), refits.end(), estimate) - refits.begin();
  const auto up_to = std::upper_bound(refits.begin(), refits.end(), estimate) - refits.begin();
  const double n = static_cast<double>(refits.size());
  const double share = std::clamp((static_cast<double>(below) + 0.5 * static_cast<double>(up_to - below)) / n,
                                  1.0 / (n + 1), n / (n + 1));
  const double z0 = normal_quantile(share), z = normal_quantile(0.975);
  return {quantile(refits, normal_cdf(2 * z0 - z)), quantile(refits, normal_cdf(2 * z0 + z))};
}

}  // namespace

PsychometricIntervals bootstrap_2afc(const std::vector<PsychometricLevel>& levels, const PsychometricFit& fit,
                                     int resamples, std::uint64_t seed) {
  PsychometricIntervals out;
  if (!fit.ok || resamples < 20) return out;
  SplitMix64 rng(seed);  // the study's own generator: the same draws on every machine
  double x_min = levels.empty() ? 0 : levels.front().x, x_max = x_min;
  for (const PsychometricLevel& l : levels) x_min = std::min(x_min, l.x), x_max = std::max(x_max, l.x);
  std::vector<double> thresholds, slopes;
  std::vector<PsychometricLevel> drawn = levels;
  for (int r = 0; r < resamples; ++r) {
    for (PsychometricLevel& l : drawn) {
      const double p = psychometric_2afc(l.x, fit.threshold, fit.slope);
      l.correct = 0;
      for (int k = 0; k < l.trials; ++k) l.correct += rng.unit() < p;
    }
    PsychometricFit refit = refit_psychometric_2afc(drawn, fit);
    if (!refit.ok) refit = fit_psychometric_2afc(drawn, kBootstrapGrid);
    if (!refit.ok) continue;
    thresholds.push_back(refit.threshold);
    slopes.push_back(refit.slope);
    if (refit.threshold < x_min || refit.threshold > x_max) ++out.extrapolated;
  }
  out.resamples = static_cast<int>(thresholds.size());
  if (out.resamples < 20) return out;
  out.threshold = bias_corrected(thresholds, fit.threshold);
  out.slope = bias_corrected(slopes, fit.slope);
  out.ok = true;
  return out;
}

}  // namespace mallet::study
