#include "core/study/staircase.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::study {

double staircase_target(int down) { return std::pow(0.5, 1.0 / std::max(down, 1)); }

Staircase::Staircase(StaircaseRule rule) : rule_(std::move(rule)) {
  rule_.down = std::max(rule_.down, 1);
  if (rule_.steps.empty()) rule_.steps = {1.0};
  level_ = std::clamp(rule_.start, rule_.min, rule_.max);
}

double Staircase::step() const {
  const std::size_t k = std::min(reversal_levels_.size(), rule_.steps.size() - 1);
  return rule_.steps[k];
}

bool Staircase::done() const { return reversals() >= rule_.stop_reversals || trials_ >= rule_.max_trials; }

void Staircase::answer(bool correct) {
  ++trials_;
  int move = 0;
  if (correct) {
    if (++run_ >= rule_.down) move = -1;
  } else {
    move = +1;
  }
  if (move == 0) return;
  run_ = 0;
  // A turn: the level where it turned is a reversal (recorded before the step it starts).
  if (direction_ != 0 && move != direction_) reversal_levels_.push_back(level_);
  direction_ = move;
  level_ = std::clamp(level_ + move * step(), rule_.min, rule_.max);
}

std::optional<double> Staircase::threshold() const {
  const int n = rule_.threshold_reversals;
  if (n <= 0 || reversals() < n) return std::nullopt;
  double sum = 0;
  for (auto it = reversal_levels_.end() - n; it != reversal_levels_.end(); ++it) sum += *it;
  return sum / n;
}

}  // namespace mallet::study
