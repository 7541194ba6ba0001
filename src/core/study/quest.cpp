#include "core/study/quest.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::study {

double quest_p_correct(const QuestModel& m, double threshold, double x) {
  const double rise = m.shape == QuestShape::weibull
                          ? (x <= 0 ? 0.0 : 1.0 - std::exp(-std::pow(x / threshold, m.beta)))
                          : 1.0 / (1.0 + std::exp(-m.beta * (x - threshold)));
  return m.gamma + (1.0 - m.gamma - m.delta) * rise;
}

Quest::Quest(QuestModel model, QuestPrior prior, int grid_points) : model_(model), prior_(prior) {
  const int n = std::max(grid_points, 2);
  if (!(prior_.hi > prior_.lo)) prior_.hi = prior_.lo + 1;
  if (!(prior_.sd > 0)) prior_.sd = 1;
  thresholds_.resize(static_cast<std::size_t>(n));
  log_posterior_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double t = prior_.lo + (prior_.hi - prior_.lo) * i / (n - 1);
    const double z = (t - prior_.mean) / prior_.sd;
    thresholds_[static_cast<std::size_t>(i)] = t;
    log_posterior_[static_cast<std::size_t>(i)] = -0.5 * z * z;
  }
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

double Quest::mean() const {
  const std::vector<double> w = weights();
  double m = 0;
  for (std::size_t i = 0; i < w.size(); ++i) m += w[i] * thresholds_[i];
  return m;
}

double Quest::mode() const {
  const auto best = std::max_element(log_posterior_.begin(), log_posterior_.end());
  return thresholds_[static_cast<std::size_t>(best - log_posterior_.begin())];
}

double Quest::sd() const {
  const std::vector<double> w = weights();
  const double m = mean();
  double v = 0;
  for (std::size_t i = 0; i < w.size(); ++i) v += w[i] * (thresholds_[i] - m) * (thresholds_[i] - m);
  return std::sqrt(v);
}

}  // namespace mallet::study
