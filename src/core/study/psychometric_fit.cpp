#include "core/study/psychometric_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mallet::study {

namespace {

double log_likelihood(const std::vector<PsychometricLevel>& levels, double threshold, double slope) {
  double ll = 0;
  for (const PsychometricLevel& l : levels) {
    const double p = std::clamp(psychometric_2afc(l.x, threshold, slope), 1e-12, 1.0 - 1e-12);
    ll += l.correct * std::log(p) + (l.trials - l.correct) * std::log(1.0 - p);
  }
  return ll;
}

}  // namespace

PsychometricFit fit_psychometric_2afc(const std::vector<PsychometricLevel>& input) {
  std::map<double, PsychometricLevel> merged;
  for (const PsychometricLevel& l : input) {
    if (l.trials <= 0 || !std::isfinite(l.x)) continue;
    PsychometricLevel& m = merged[l.x];
    m.x = l.x;
    m.trials += l.trials;
    m.correct += l.correct;
  }
  std::vector<PsychometricLevel> levels;
  for (const auto& [x, l] : merged) levels.push_back(l);
  PsychometricFit fit;
  fit.levels = static_cast<int>(levels.size());
  if (levels.size() < 3) {
    fit.reason = "not enough levels (" + std::to_string(levels.size()) +
                 " distinct stimulus difference" + (levels.size() == 1 ? "" : "s") + "; a fit needs 3)";
    return fit;
  }
  const double x_min = levels.front().x, x_max = levels.back().x;
  const double span = x_max - x_min;
  // Bounds: the threshold within one span of the tested range; the slope from "accuracy
  // barely changes over 100 spans" to "it jumps within a hundredth of one".
  const double t_lo = x_min - span, t_hi = x_max + span;
  const double ls_lo = std::log(0.01 / span), ls_hi = std::log(100.0 / span);

  constexpr int kPoints = 81;
  double t_a = t_lo, t_b = t_hi, s_a = ls_lo, s_b = ls_hi;
  double best_t = 0, best_ls = 0, best = -std::numeric_limits<double>::infinity();
  for (int round = 0; round < 6; ++round) {
    for (int i = 0; i < kPoints; ++i) {
      const double t = t_a + (t_b - t_a) * i / (kPoints - 1);
      for (int j = 0; j < kPoints; ++j) {
        const double ls = s_a + (s_b - s_a) * j / (kPoints - 1);
        const double ll = log_likelihood(levels, t, std::exp(ls));
        if (ll > best) best = ll, best_t = t, best_ls = ls;
      }
    }
    // Zoom in: four grid steps either side of the best point, kept inside the bounds.
    const double dt = 4 * (t_b - t_a) / (kPoints - 1), ds = 4 * (s_b - s_a) / (kPoints - 1);
    t_a = std::max(t_lo, best_t - dt), t_b = std::min(t_hi, best_t + dt);
    s_a = std::max(ls_lo, best_ls - ds), s_b = std::min(ls_hi, best_ls + ds);
  }
  fit.ok = true;
  fit.threshold = best_t;
  fit.slope = std::exp(best_ls);
  fit.log_likelihood = best;
  const double tolerance = 1e-6 * span;
  if (best_t > x_max + tolerance || best_t < x_min - tolerance)
    fit.reason = "threshold outside the tested range: extrapolated";
  if (best_ls >= ls_hi - 1e-9) fit.reason += std::string(fit.reason.empty() ? "" : "; ") + "slope at its upper bound (a step)";
  if (best_ls <= ls_lo + 1e-9) fit.reason += std::string(fit.reason.empty() ? "" : "; ") + "slope at its lower bound (flat)";
  return fit;
}

}  // namespace mallet::study
