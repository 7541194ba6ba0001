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

//! The levels merged by x (trials and correct answers added), in ascending x.
std::vector<PsychometricLevel> merged_levels(const std::vector<PsychometricLevel>& input) {
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
  return levels;
}

}  // namespace

PsychometricFit refit_psychometric_2afc(const std::vector<PsychometricLevel>& input, const PsychometricFit& near) {
  const std::vector<PsychometricLevel> levels = merged_levels(input);
  PsychometricFit fit;
  fit.levels = static_cast<int>(levels.size());
  if (levels.size() < 3 || !near.ok) return fit;
  const double x_min = levels.front().x, x_max = levels.back().x, span = x_max - x_min;
  const double t_lo = x_min - span, t_hi = x_max + span;
  const double ls_lo = std::log(0.01 / span), ls_hi = std::log(100.0 / span);
  // Newton's method in (threshold, log slope), derivatives by central differences, each step
  // halved until the likelihood rises: a few dozen likelihoods where the grid takes thousands.
  auto ll = [&](double t, double ls) { return log_likelihood(levels, t, std::exp(ls)); };
  double t = near.threshold, ls = std::log(near.slope), f = ll(t, ls);
  const double ht = 1e-4 * span, hs = 1e-4;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double ftp = ll(t + ht, ls), ftm = ll(t - ht, ls), fsp = ll(t, ls + hs), fsm = ll(t, ls - hs);
    const double fpp = ll(t + ht, ls + hs), fpm = ll(t + ht, ls - hs), fmp = ll(t - ht, ls + hs),
                 fmm = ll(t - ht, ls - hs);
    const double gt = (ftp - ftm) / (2 * ht), gs = (fsp - fsm) / (2 * hs);
    const double htt = (ftp - 2 * f + ftm) / (ht * ht), hss = (fsp - 2 * f + fsm) / (hs * hs);
    const double hts = (fpp - fpm - fmp + fmm) / (4 * ht * hs);
    const double det = htt * hss - hts * hts;
    if (!(htt < 0 && det > 0)) return fit;  // not a maximum's neighbourhood: the grid decides
    double dt = -(hss * gt - hts * gs) / det, ds = -(htt * gs - hts * gt) / det;
    const double shrink = std::min({1.0, span / std::max(std::abs(dt), 1e-300), 1.0 / std::max(std::abs(ds), 1e-300)});
    dt *= shrink, ds *= shrink;
    double next = ll(t + dt, ls + ds);
    for (int halving = 0; halving < 20 && !(next >= f); ++halving) {
      dt /= 2, ds /= 2;
      next = ll(t + dt, ls + ds);
    }
    if (!(next >= f)) return fit;
    t += dt, ls += ds, f = next;
    if (t < t_lo || t > t_hi || ls < ls_lo || ls > ls_hi) return fit;  // at a bound: the grid's case
    if (std::abs(dt) < 1e-7 * span && std::abs(ds) < 1e-7) {
      fit.ok = true;
      fit.threshold = t;
      fit.slope = std::exp(ls);
      fit.log_likelihood = f;
      if (t > x_max || t < x_min) fit.reason = "threshold outside the tested range: extrapolated";
      return fit;
    }
  }
  return fit;
}

PsychometricFit fit_psychometric_2afc(const std::vector<PsychometricLevel>& input, FitGrid grid) {
  const std::vector<PsychometricLevel> levels = merged_levels(input);
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

  const int points = std::max(grid.points, 9);
  double t_a = t_lo, t_b = t_hi, s_a = ls_lo, s_b = ls_hi;
  double best_t = 0, best_ls = 0, best = -std::numeric_limits<double>::infinity();
  for (int round = 0; round < grid.rounds; ++round) {
    for (int i = 0; i < points; ++i) {
      const double t = t_a + (t_b - t_a) * i / (points - 1);
      for (int j = 0; j < points; ++j) {
        const double ls = s_a + (s_b - s_a) * j / (points - 1);
        const double ll = log_likelihood(levels, t, std::exp(ls));
        if (ll > best) best = ll, best_t = t, best_ls = ls;
      }
    }
    // Zoom in: four grid steps either side of the best point, kept inside the bounds.
    const double dt = 4 * (t_b - t_a) / (points - 1), ds = 4 * (s_b - s_a) / (points - 1);
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
