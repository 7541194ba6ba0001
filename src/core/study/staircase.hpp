#pragma once
// A transformed up-down staircase (Levitt 1971, "Transformed up-down methods in
// psychoacoustics"): the stimulus difference goes down one step after `down` correct answers
// in a row and up one step after any wrong answer, so that it hovers where a correct answer
// is as likely as not to end a run: P(correct) = 0.5^(1/down), 70.7 % for 1-up-2-down and
// 79.4 % for 1-up-3-down. A reversal is a turn from going down to going up or back; the step
// shrinks with the reversals (steps[k] after k of them, the last one thereafter), the
// staircase stops after `stop_reversals` (or `max_trials`), and its threshold is the mean
// level at the last `threshold_reversals` reversals, never counting the first
// `discard_reversals`.
//
// A step is added to the level (linear, in %) or multiplies it (db: by 10^(step/20); log: by
// 10^step), PsychoPy's StairHandler stepType 'lin', 'db' and 'log'. With
// initial_one_up_one_down the rule is 1-up-1-down until the first reversal (StairHandler's
// applyInitialRule, its default): the trial that makes the first reversal still steps by it,
// and 1-up-`down`-down holds from the next.
//
// Its state is a function of the answers alone: a session resumed after a crash replays the
// rows it finds and goes on exactly where it stopped.
#include <optional>
#include <vector>

#include "core/enum_names.hpp"

namespace mallet::study {

//! How a step changes the level: adds to it, or multiplies it by a factor in dB or log10 units.
enum class StaircaseStepType { linear, db, log };
inline constexpr EnumNames<StaircaseStepType, 3> kStaircaseStepTypeNames{
    {{StaircaseStepType::linear, "linear"}, {StaircaseStepType::db, "db"}, {StaircaseStepType::log, "log"}}};

//! The factor a step of `step` multiplies the level by (db, log); linear steps add, and have none.
double staircase_step_factor(StaircaseStepType type, double step);

struct StaircaseRule {
  int down = 2;                          //!< correct answers in a row for one step down (1-up-N-down)
  double start = 30;                     //!< the first difference tested (%)
  std::vector<double> steps{8, 4, 2};    //!< step size after 0, 1, 2… reversals (%, dB or log10 units)
  double min = 0.5, max = 100;           //!< the differences it may test (%)
  int stop_reversals = 12;               //!< done after this many reversals
  int threshold_reversals = 8;           //!< the threshold: mean level at the last this many
  int max_trials = 200;                  //!< done after this many trials, reversals or not
  StaircaseStepType step_type = StaircaseStepType::linear;
  bool initial_one_up_one_down = false;  //!< 1-up-1-down until the first reversal
  int discard_reversals = 0;             //!< the first this many never count in the threshold
};

//! Where the rule converges: the P(correct) at which `down` correct in a row is as likely as not.
double staircase_target(int down);

class Staircase {
 public:
  explicit Staircase(StaircaseRule rule);

  //! The difference to test next (%).
  double level() const { return level_; }
  //! The answer of the trial at level(). `tested_pct`: the difference the trial really
  //! tested when that is not level() (the grid's nearest, when steps multiply): a reversal is
  //! recorded there, as StairHandler's addResponse(result, intensity) records it, while the
  //! next level still steps from level().
  void answer(bool correct, std::optional<double> tested_pct = std::nullopt);
  bool done() const;

  int trials() const { return trials_; }
  int reversals() const { return static_cast<int>(reversal_levels_.size()); }
  const std::vector<double>& reversal_levels() const { return reversal_levels_; }
  //! The current step size (%, or dB or log10 units as step_type says).
  double step() const;
  //! Mean level at the last threshold_reversals reversals after the first discard_reversals;
  //! nothing before there are that many (discard_reversals + threshold_reversals in all).
  std::optional<double> threshold() const;
  const StaircaseRule& rule() const { return rule_; }

 private:
  StaircaseRule rule_;
  double level_;
  int trials_ = 0;
  int run_ = 0;        //!< correct answers in a row since the last step
  int direction_ = 0;  //!< the last step: −1 down, +1 up, 0 none yet
  std::vector<double> reversal_levels_;
};

}  // namespace mallet::study
