#include "core/study/quest.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::study {

namespace {

//! The weights' mean and SD of `v` (the order of the sums is the one every release used, so
//! a linear track's numbers stay bit for bit what they were).
struct Moments {
  double mean = 0, sd = 0;
};
Moments moments(const std::vector<double>& w, const std::vector<double>& v) {
  Moments out;
  for (std::size_t i = 0; i < w.size(); ++i) out.mean += w[i] * v[i];
  double var = 0;
  for (std::size_t i = 0; i < w.size(); ++i) var += w[i] * (v[i] - out.mean) * (v[i] - out.mean);
  out.sd = std::sqrt(var);
  return out;
}

}  // namespace

double quest_p_correct(const QuestModel& m, double threshold, double x) {
  double rise = 0;
  if (m.shape == QuestShape::weibull) {
    // (x/T)^β is 10^(β·(log10 x − log10 T)): one curve on either scale.
    rise = x <= 0 ? 0.0 : 1.0 - std::exp(-std::pow(x / threshold, m.beta));
  } else if (m.scale == QuestScale::linear) {
    rise = 1.0 / (1.0 + std::exp(-m.beta * (x - threshold)));
  } else {
    rise = x <= 0 ? 0.0 : 1.0 / (1.0 + std::exp(-m.beta * (std::log10(x) - std::log10(threshold))));
  }
  return m.gamma + (1.0 - m.gamma - m.delta) * rise;
}

Quest::Quest(QuestModel model, QuestPrior prior, int grid_points) : model_(model), prior_(prior) {
  const int n = std::max(grid_points, 2);
  const bool log = model_.scale == QuestScale::log10;
  if (log && !(prior_.lo > 0)) prior_.lo = 1e-3;  // log10 needs a positive range
  if (!(prior_.hi > prior_.lo)) prior_.hi = prior_.lo + 1;
  if (!(prior_.sd > 0)) prior_.sd = 1;
  model_.quantile = std::clamp(model_.quantile, 0.0, 1.0);
  thresholds_.resize(static_cast<std::size_t>(n));
  on_scale_.resize(static_cast<std::size_t>(n));
  log_posterior_.resize(static_cast<std::size_t>(n));
  const double lo = log ? std::log10(prior_.lo) : prior_.lo;
  const double hi = log ? std::log10(prior_.hi) : prior_.hi;
  for (int i = 0; i < n; ++i) {
    const double u = lo + (hi - lo) * i / (n - 1);
    const double z = (u - prior_.mean) / prior_.sd;
    thresholds_[static_cast<std::size_t>(i)] = to_pct(u);
    on_scale_[static_cast<std::size_t>(i)] = u;
    log_posterior_[static_cast<std::size_t>(i)] = -0.5 * z * z;
  }
}

double Quest::to_pct(double v) const { return model_.scale == QuestScale::log10 ? std::pow(10.0, v) : v; }

double Quest::level() const {
  switch (model_.placement) {
    case QuestPlacement::mode: return mode();
    case QuestPlacement::quantile: return quantile(model_.quantile);
    case QuestPlacement::mean: break;
  }
  return mean();
}

void Quest::answer(double x, bool correct) {
  ++trials_;
  for (std::size_t i = 0; i < thresholds_.size(); ++i) {
    const double p = std::clamp(quest_p_correct(model_, thresholds_[i], x), 1e-12, 1.0 - 1e-12);
    log_posterior_[i] += std::log(correct ? p : 1.0 - p);
  }
}

std::vector<double> Quest::weights() const {
  const double top = *std::max_element(log_posterior_.begin(), log_posterior_.end());
  std::vector<double> w(log_posterior_.size());
  double sum = 0;
  for (std::size_t i = 0; i < w.size(); ++i) sum += w[i] = std::exp(log_posterior_[i] - top);
  for (double& v : w) v /= sum;
  return w;
}

double Quest::mean() const { return to_pct(mean_on_scale()); }

double Quest::mean_on_scale() const { return moments(weights(), on_scale_).mean; }

double Quest::sd_on_scale() const { return moments(weights(), on_scale_).sd; }

double Quest::mode() const {
  const auto best = std::max_element(log_posterior_.begin(), log_posterior_.end());
  return thresholds_[static_cast<std::size_t>(best - log_posterior_.begin())];
}

double Quest::sd() const { return moments(weights(), thresholds_).sd; }

double Quest::quantile(double q) const {
  // The posterior's cumulative sums at the grid's points, interpolated linearly between the
  // two around q (below the first point: the first point).
  const std::vector<double> w = weights();
  const double target = std::clamp(q, 0.0, 1.0);
  double below = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double at = below + w[i];
    if (at >= target) {
      if (i == 0) return thresholds_[0];
      // below < target <= at, so at > below: the division is safe.
      const double f = (target - below) / (at - below);
      return to_pct(on_scale_[i - 1] + f * (on_scale_[i] - on_scale_[i - 1]));
    }
    below = at;
  }
  return thresholds_.back();
}

}  // namespace mallet::study
