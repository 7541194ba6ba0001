#include "core/study/psychometric_fit.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <map>

#include <fmt/format.h>

namespace mallet::study {

namespace {

constexpr int kThreshold = 0, kLogSlope = 1, kLapse = 2;
using Point = std::array<double, 3>;  // threshold, log slope, lapse

//! The likelihood over the box, in the coordinates the search climbs in: threshold, log slope
//! (so that "ten times steeper" is the same distance everywhere) and lapse. A coordinate whose
//! bounds are equal is fixed (the lapse when it is not fitted; the slope in a profile).
struct Climb {
  const std::vector<PsychometricLevel>& levels;
  const PsychometricModel& model;
  Point lo, hi;

  double range(int i) const { return hi[i] - lo[i]; }
  bool fixed(int i) const { return !(hi[i] > lo[i]); }
  double ll(const Point& u) const {
    return psychometric_log_likelihood(levels, model, {u[kThreshold], std::exp(u[kLogSlope]), u[kLapse]});
  }
  Point project(Point u) const {
    for (int i = 0; i < 3; ++i) u[i] = std::clamp(u[i], lo[i], hi[i]);
    return u;
  }

  //! The gradient and Hessian at u by central differences, the stencil kept inside the box
  //! (moved in from a side by one step, the gradient carried back to u by the Hessian).
  void derivatives(const Point& u, Point& g, std::array<Point, 3>& h) const {
    Point c = u, step{};
    for (int i = 0; i < 3; ++i) {
      if (fixed(i)) continue;
      step[i] = 1e-5 * range(i);
      c[i] = std::clamp(u[i], lo[i] + step[i], hi[i] - step[i]);
    }
    const double f = ll(c);
    auto at = [&](int i, double di, int j, double dj) {
      Point p = c;
      p[i] += di * step[i];
      p[j] += dj * step[j];
      return ll(p);
    };
    g = {};
    h = {};
    for (int i = 0; i < 3; ++i) {
      if (fixed(i)) continue;
      Point plus = c, minus = c;
      plus[i] += step[i], minus[i] -= step[i];
      const double fp = ll(plus), fm = ll(minus);
      g[i] = (fp - fm) / (2 * step[i]);
      h[i][i] = (fp - 2 * f + fm) / (step[i] * step[i]);
      for (int j = 0; j < i; ++j) {
        if (fixed(j)) continue;
        h[i][j] = h[j][i] = (at(i, 1, j, 1) - at(i, 1, j, -1) - at(i, -1, j, 1) + at(i, -1, j, -1)) /
                            (4 * step[i] * step[j]);
      }
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) g[i] += h[i][j] * (u[j] - c[j]);
  }

  //! Projected Newton's method from `u`: the coordinates pressed against a side of the box
  //! (at it, the gradient pointing out) are held there and the others take a Newton step
  //! (Marquardt's where the Hessian is not a maximum's), halved until the likelihood rises.
  //! It ends when no step rises, the step is under 1e-10 of the box or the rise under 1e-13.
  Point climb(Point u, double& f) const {
    u = project(u);
    f = ll(u);
    for (int iteration = 0; iteration < 200; ++iteration) {
      Point g;
      std::array<Point, 3> h;
      derivatives(u, g, h);
      std::array<int, 3> free{};
      int n = 0;
      for (int i = 0; i < 3; ++i) {
        if (fixed(i)) continue;
        const double side = 1e-9 * range(i);
        if ((u[i] <= lo[i] + side && g[i] <= 0) || (u[i] >= hi[i] - side && g[i] >= 0)) continue;
        free[n++] = i;
      }
      if (n == 0) break;
      Point d{};
      bool direction = newton_step(g, h, free, n, d);
      for (double mu = 1e-3; !direction && mu < 1e9; mu *= 10) direction = newton_step(g, h, free, n, d, mu);
      if (!direction) {
        double norm = 0;
        for (int k = 0; k < n; ++k) norm += std::pow(g[free[k]] * range(free[k]), 2);
        norm = std::sqrt(norm);
        if (!(norm > 0)) break;
        for (int k = 0; k < n; ++k) d[free[k]] = 0.1 * range(free[k]) * g[free[k]] * range(free[k]) / norm;
      }
      bool rose = false;
      Point next{};
      double f_next = f;
      for (int halving = 0; halving < 50; ++halving) {
        Point trial = u;
        for (int i = 0; i < 3; ++i) trial[i] += d[i];
        trial = project(trial);
        f_next = ll(trial);
        if (f_next > f) {
          next = trial;
          rose = true;
          break;
        }
        for (double& di : d) di /= 2;
      }
      if (!rose) break;
      bool small = true;
      for (int i = 0; i < 3; ++i)
        if (!fixed(i) && std::abs(next[i] - u[i]) > 1e-10 * range(i)) small = false;
      const double rise = f_next - f;
      u = next, f = f_next;
      if (small || rise < 1e-13) break;
    }
    return u;
  }

  //! Solves (−H + μ·S)·d = g over the free coordinates by Cholesky, S the diagonal of |H|
  //! (Marquardt's scaling): μ = 0 is Newton's step, a larger μ a shorter step turned towards
  //! the gradient, an ascent direction whatever the curvature. False when −H (at μ = 0) is
  //! not positive definite there (not a maximum's neighbourhood).
  static bool newton_step(const Point& g, const std::array<Point, 3>& h, const std::array<int, 3>& free, int n,
                          Point& d, double mu = 0) {
    double l[3][3] = {};
    for (int a = 0; a < n; ++a)
      for (int b = 0; b <= a; ++b) {
        double s = -h[free[a]][free[b]];
        if (a == b) s += mu * std::max(std::abs(h[free[a]][free[a]]), 1e-12);
        for (int k = 0; k < b; ++k) s -= l[a][k] * l[b][k];
        if (a == b) {
          if (!(s > 0)) return false;
          l[a][a] = std::sqrt(s);
        } else {
          l[a][b] = s / l[b][b];
        }
      }
    double y[3];
    for (int a = 0; a < n; ++a) {
      double s = g[free[a]];
      for (int k = 0; k < a; ++k) s -= l[a][k] * y[k];
      y[a] = s / l[a][a];
    }
    for (int a = n - 1; a >= 0; --a) {
      double s = y[a];
      for (int k = a + 1; k < n; ++k) s -= l[k][a] * d[free[k]];
      d[free[a]] = s / l[a][a];
    }
    return true;
  }
};

FitBox box_for(const std::vector<PsychometricLevel>& levels, const FitOptions& options) {
  const double x_min = levels.front().x, x_max = levels.back().x, span = x_max - x_min;
  FitBox box;
  box.threshold_lo = x_min - span;
  box.threshold_hi = x_max + span;
  if (x_min >= 0 && box.threshold_lo <= 0) {
    box.threshold_lo = 0;
    box.threshold_lo_is_zero = true;
  }
  if (options.model.shape == PsychometricShape::weibull) {
    // The Weibull's threshold is a scale (> 0) and its slope an exponent: "a jump within a
    // hundredth of the span" near the largest difference is an exponent of 100·x_max/span.
    box.threshold_lo = std::max(box.threshold_lo, 1e-6 * span);
    const double reach = std::max(x_max, 1e-6 * span) / span;
    box.slope_lo = 0.01 * reach;
    box.slope_hi = 100 * reach;
  } else {
    box.slope_lo = 0.01 / span;
    box.slope_hi = 100 / span;
  }
  box.lapse_lo = options.fit_lapse ? 0 : options.lapse;
  box.lapse_hi = options.fit_lapse ? options.lapse_limit : options.lapse;
  return box;
}

Climb climb_for(const std::vector<PsychometricLevel>& levels, const FitOptions& options, const FitBox& box) {
  return {levels,
          options.model,
          {box.threshold_lo, std::log(box.slope_lo), box.lapse_lo},
          {box.threshold_hi, std::log(box.slope_hi), box.lapse_hi}};
}

//! The coarse grid's best few points, each climbed from; the highest summit wins.
Point search(const Climb& c, double& best) {
  constexpr int kPoints = 21, kLapses = 3, kStarts = 3;
  std::vector<std::pair<double, Point>> grid;
  const int lapses = c.fixed(kLapse) ? 1 : kLapses;
  for (int i = 0; i < kPoints; ++i)
    for (int j = 0; j < kPoints; ++j)
      for (int k = 0; k < lapses; ++k) {
        const Point u{c.lo[kThreshold] + c.range(kThreshold) * i / (kPoints - 1),
                      c.lo[kLogSlope] + c.range(kLogSlope) * j / (kPoints - 1),
                      lapses == 1 ? c.lo[kLapse] : c.lo[kLapse] + c.range(kLapse) * k / (lapses - 1)};
        grid.emplace_back(c.ll(u), u);
      }
  std::partial_sort(grid.begin(), grid.begin() + kStarts, grid.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  best = -std::numeric_limits<double>::infinity();
  Point summit{};
  for (int s = 0; s < kStarts; ++s) {
    double f = 0;
    const Point u = c.climb(grid[static_cast<std::size_t>(s)].second, f);
    if (f > best) best = f, summit = u;
  }
  return summit;
}

void join(std::string& reason, const std::string& more) { reason += (reason.empty() ? "" : "; ") + more; }

//! The fit's numbers and what its maximum's place means (the top of psychometric_fit.hpp).
PsychometricFit describe(const std::vector<PsychometricLevel>& levels, const FitOptions& options, const FitBox& box,
                         const Point& u, double ll) {
  PsychometricFit fit;
  fit.ok = true;
  fit.levels = static_cast<int>(levels.size());
  fit.box = box;
  fit.threshold = u[kThreshold];
  fit.slope = std::exp(u[kLogSlope]);
  fit.lapse = u[kLapse];
  fit.log_likelihood = ll;
  const Climb c = climb_for(levels, options, box);
  auto at_lo = [&](int i) { return !c.fixed(i) && u[i] <= c.lo[i] + 1e-7 * c.range(i); };
  auto at_hi = [&](int i) { return !c.fixed(i) && u[i] >= c.hi[i] - 1e-7 * c.range(i); };
  fit.flat = at_lo(kLogSlope);
  fit.step = at_hi(kLogSlope);
  // A step beyond the tested differences is as likely anywhere out there: no estimate either.
  const bool step_out_below = fit.step && fit.threshold < levels.front().x;
  const bool step_out_above = fit.step && fit.threshold > levels.back().x;
  fit.threshold_below = (at_lo(kThreshold) || step_out_below) && !fit.flat;
  fit.threshold_above = (at_hi(kThreshold) || step_out_above) && !fit.flat;
  fit.lapse_at_limit = options.fit_lapse && at_hi(kLapse);
  fit.extrapolated = fit.has_threshold() && (fit.threshold < levels.front().x || fit.threshold > levels.back().x);
  if (fit.flat) join(fit.reason, "no rise in accuracy over the tested range: no threshold");
  if (fit.threshold_below) join(fit.reason, "threshold below the tested range: no estimate");
  if (fit.threshold_above) join(fit.reason, "threshold above the tested range: no estimate");
  if (fit.extrapolated) join(fit.reason, "threshold outside the tested range: extrapolated");
  if (fit.lapse_at_limit) join(fit.reason, fmt::format("lapse at its limit {:g}", options.lapse_limit));
  // Goodness of fit against the saturated model (each level its own proportion).
  for (const PsychometricLevel& l : levels) {
    const double p = std::clamp(psychometric_p(options.model, {fit.threshold, fit.slope, fit.lapse}, l.x), 1e-12,
                                1.0 - 1e-12);
    const double k = l.correct, n = l.trials;
    const double d = 2 * ((k > 0 ? k * std::log(k / (n * p)) : 0.0) +
                          (n - k > 0 ? (n - k) * std::log((n - k) / (n * (1 - p))) : 0.0));
    fit.deviance += d;
    fit.residuals.push_back((k / n >= p ? 1.0 : -1.0) * std::sqrt(std::max(d, 0.0)));
  }
  return fit;
}

constexpr double kHalfChiSquare95 = 1.920729410347062;  //!< χ²₁(0.95)/2

//! How far one coordinate may go from the fit towards `to` with the profile likelihood (the
//! other coordinates climbed to their best there) within χ²₁(0.95)/2 of the maximum, found
//! by bisection: the likelihood-ratio 95 % limit on that side (`to` itself when it is within).
double profile_limit(const std::vector<PsychometricLevel>& levels, const FitOptions& options,
                     const PsychometricFit& fit, int coordinate, double to) {
  const Climb whole = climb_for(levels, options, fit.box);
  const Point at_fit{fit.threshold, std::log(fit.slope), fit.lapse};
  auto within = [&](double value) {
    Climb c = whole;
    c.lo[coordinate] = c.hi[coordinate] = value;
    Point start = at_fit;
    start[coordinate] = value;
    double f = 0, from_grid = 0;
    c.climb(start, f);
    search(c, from_grid);
    return std::max(f, from_grid) >= fit.log_likelihood - kHalfChiSquare95;
  };
  if (within(to)) return to;
  double kept = at_fit[coordinate], refused = to;
  for (int i = 0; i < 40; ++i) {
    const double mid = (kept + refused) / 2;
    (within(mid) ? kept : refused) = mid;
  }
  return kept;
}

}  // namespace

double psychometric_log_likelihood(const std::vector<PsychometricLevel>& levels, const PsychometricModel& model,
                                   const PsychometricParams& params) {
  double ll = 0;
  for (const PsychometricLevel& l : levels) {
    const double p = std::clamp(psychometric_p(model, params, l.x), 1e-12, 1.0 - 1e-12);
    ll += l.correct * std::log(p) + (l.trials - l.correct) * std::log(1.0 - p);
  }
  return ll;
}

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

PsychometricFit fit_psychometric(const std::vector<PsychometricLevel>& input, const FitOptions& options) {
  const std::vector<PsychometricLevel> levels = merged_levels(input);
  if (levels.size() < 3) {
    PsychometricFit fit;
    fit.levels = static_cast<int>(levels.size());
    fit.reason = "not enough levels (" + std::to_string(levels.size()) + " distinct stimulus difference" +
                 (levels.size() == 1 ? "" : "s") + "; a fit needs 3)";
    return fit;
  }
  const FitBox box = box_for(levels, options);
  double best = 0;
  const Point u = search(climb_for(levels, options, box), best);
  PsychometricFit fit = describe(levels, options, box, u, best);
  if (fit.extrapolated) {
    // Beyond the tested differences the likelihood may be as high with the threshold at the
    // search's edge (chance at every level: any curve still flat there fits): then the data
    // do not place it, and it is no estimate.
    Climb at_edge = climb_for(levels, options, box);
    const bool above = fit.threshold > levels.back().x;
    at_edge.lo[kThreshold] = at_edge.hi[kThreshold] = above ? box.threshold_hi : box.threshold_lo;
    double edge = 0;
    search(at_edge, edge);
    if (edge >= fit.log_likelihood - 1e-6) {
      (above ? fit.threshold_above : fit.threshold_below) = true;
      fit.extrapolated = false;
      fit.reason = above ? "threshold above the tested range: no estimate" : "threshold below the tested range: no estimate";
      if (fit.lapse_at_limit) join(fit.reason, fmt::format("lapse at its limit {:g}", options.lapse_limit));
      return fit;
    }
  }
  if (fit.step && fit.has_threshold()) {
    // A step's slope is only bounded below, and its threshold is anywhere the step may stand
    // between the levels around it: both from the likelihood, which a bootstrap of a step
    // (every refit the same step) cannot show.
    fit.slope_at_least = std::exp(profile_limit(levels, options, fit, kLogSlope, std::log(box.slope_lo)));
    fit.step_threshold_lo = profile_limit(levels, options, fit, kThreshold, box.threshold_lo);
    fit.step_threshold_hi = profile_limit(levels, options, fit, kThreshold, box.threshold_hi);
    join(fit.reason, fmt::format("a step: slope at least {:.3g}", fit.slope_at_least));
  }
  return fit;
}

PsychometricFit refit_psychometric(const std::vector<PsychometricLevel>& input, const FitOptions& options,
                                   const PsychometricFit& near) {
  const std::vector<PsychometricLevel> levels = merged_levels(input);
  if (levels.size() < 3 || !near.ok) return fit_psychometric(input, options);
  const FitBox box = box_for(levels, options);
  const Climb c = climb_for(levels, options, box);
  // With a fitted lapse the likelihood can have a second summit (a steeper curve with more
  // lapses, or a shallower one without) far from the data's: the whole search decides.
  if (!c.fixed(kLapse)) {
    double best = 0;
    const Point w = search(c, best);
    return describe(levels, options, box, w, best);
  }
  double f = 0;
  const Point u = c.climb({near.threshold, std::log(near.slope), near.lapse}, f);
  PsychometricFit fit = describe(levels, options, box, u, f);
  // A summit with the threshold and the slope inside the box, where the likelihood curves
  // down in every direction it may move (the lapse may rest on 0 or its limit), is the
  // maximum the whole search would find; with the threshold or the slope on a side, the
  // whole search decides (a resample of a step may have its maximum elsewhere on the sides).
  if (!fit.step && !fit.flat && !fit.threshold_below && !fit.threshold_above) {
    Point g;
    std::array<Point, 3> h;
    c.derivatives(u, g, h);
    std::array<int, 3> free{};
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const double side = 1e-9 * c.range(i);
      if (c.fixed(i) || (i == kLapse && ((u[i] <= c.lo[i] + side && g[i] <= 0) || (u[i] >= c.hi[i] - side && g[i] >= 0))))
        continue;
      free[n++] = i;
    }
    Point d{};
    if (Climb::newton_step(g, h, free, n, d)) return fit;
  }
  double best = 0;
  const Point w = search(c, best);
  return best > f ? describe(levels, options, box, w, best) : fit;
}

}  // namespace mallet::study
