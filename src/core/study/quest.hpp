#pragma once
// QUEST (Watson & Pelli 1983, "QUEST: a Bayesian adaptive psychometric method"): the
// threshold is a probability distribution, a prior from the protocol multiplied after each
// trial by the likelihood of its answer; each trial tests the posterior's mean (King-Smith et
// al. 1994 found the mean more efficient than Watson & Pelli's mode), and the estimate is the
// posterior's mean, mode and SD. The distribution is held on a grid of thresholds.
//
// The psychometric function of a 2AFC answer at difference x (%), with guessing γ = 0.5 and a
// lapse rate δ (answers wrong whatever the difference):
//   weibull:  P(x) = γ + (1 − γ − δ)·(1 − exp(−(x/T)^β)),  x ≥ 0   (T: ≈ 81.6 % correct at δ=0)
//   logistic: P(x) = γ + (1 − γ − δ)/(1 + exp(−β·(x − T)))          (T: 75 % correct at δ=0;
//             the fit of psychometric_fit.hpp, with β its slope)
// Like the staircase, its state is a function of the answers alone, so a resumed session
// replays its rows.
#include <vector>

namespace mallet::study {

enum class QuestShape { weibull, logistic };

struct QuestModel {
  QuestShape shape = QuestShape::weibull;
  double beta = 3.5;    //!< Weibull: the exponent; logistic: the slope per %
  double gamma = 0.5;   //!< guessing (2AFC)
  double delta = 0.01;  //!< lapses
};

struct QuestPrior {
  double mean = 20, sd = 15;    //!< the threshold's Gaussian prior (%)
  double lo = 0.5, hi = 100;    //!< the thresholds it can be, and the differences it tests (%)
};

double quest_p_correct(const QuestModel& model, double threshold, double x);

class Quest {
 public:
  Quest(QuestModel model, QuestPrior prior, int grid_points = 1000);

  //! The difference to test next: the posterior's mean, within [lo, hi].
  double level() const { return mean(); }
  void answer(double x, bool correct);

  double mean() const;
  double mode() const;
  double sd() const;
  int trials() const { return trials_; }

 private:
  QuestModel model_;
  QuestPrior prior_;
  std::vector<double> thresholds_;
  std::vector<double> log_posterior_;  //!< up to a constant: sums of logs, no underflow
  int trials_ = 0;
  //! The posterior normalised (weights summing to 1).
  std::vector<double> weights() const;
};

}  // namespace mallet::study
