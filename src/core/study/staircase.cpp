#include "core/study/staircase.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::study {

double staircase_target(int down) { return std::pow(0.5, 1.0 / std::max(down, 1)); }

double staircase_step_factor(StaircaseStepType type, double step) {
  switch (type) {
    case StaircaseStepType::db: return std::pow(10.0, step / 20.0);  // a step in dB of amplitude
    case StaircaseStepType::log: return std::pow(10.0, step);        // a step in log10 units
    case StaircaseStepType::linear: break;
  }
  return 1.0;
}

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

void Staircase::answer(bool correct, std::optional<double> tested_pct) {
  ++trials_;
  // Before the first reversal the initial phase steps down after every correct answer; the
  // trial that makes that reversal still belongs to it (as StairHandler's applyInitialRule).
  const int down = rule_.initial_one_up_one_down && reversal_levels_.empty() ? 1 : rule_.down;
  int move = 0;
  if (correct) {
    if (++run_ >= down) move = -1;
  } else {
    move = +1;
  }
  if (move == 0) return;
  run_ = 0;
  // A turn: the level where it turned is a reversal (recorded before the step it starts).
  if (direction_ != 0 && move != direction_) reversal_levels_.push_back(tested_pct.value_or(level_));
  direction_ = move;
  double next = level_ + move * step();
  if (rule_.step_type != StaircaseStepType::linear) {
    const double factor = staircase_step_factor(rule_.step_type, step());
    next = move > 0 ? level_ * factor : level_ / factor;
  }
  level_ = std::clamp(next, rule_.min, rule_.max);
}

std::optional<double> Staircase::threshold() const {
  // With at least discard + n reversals, the last n are all past the first `discard`.
  const int n = rule_.threshold_reversals;
  if (n <= 0 || reversals() < std::max(rule_.discard_reversals, 0) + n) return std::nullopt;
  double sum = 0;
  for (auto it = reversal_levels_.end() - n; it != reversal_levels_.end(); ++it) sum += *it;
  return sum / n;
}

}  // namespace mallet::study
