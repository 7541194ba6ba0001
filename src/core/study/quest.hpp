#pragma once
// QUEST (Watson & Pelli 1983, "QUEST: a Bayesian adaptive psychometric method"): the
// threshold is a probability distribution, a prior from the protocol multiplied after each
// trial by the likelihood of its answer; each trial tests a point of the posterior (by
// default its mean: King-Smith et al. 1994 found the mean more efficient than Watson &
// Pelli's mode), and the estimate is the posterior's mean, mode and SD. The distribution is
// held on a grid of thresholds.
//
// The psychometric function of a 2AFC answer at difference x (%), with guessing γ = 0.5 and a
// lapse rate δ (answers wrong whatever the difference):
//   weibull:  P(x) = γ + (1 − γ − δ)·(1 − exp(−(x/T)^β)),  x ≥ 0   (T: ≈ 81.6 % correct at δ=0)
//   logistic: P(x) = γ + (1 − γ − δ)/(1 + exp(−β·(x − T)))          (T: 75 % correct at δ=0;
//             the fit of psychometric_fit.hpp, with β its slope)
// Pelli's QUEST, and PsychoPy's QuestHandler after it, count a lapse as a blind guess
// (answered correctly with probability γ): P = δ'γ + (1 − δ')(γ + (1 − γ)·F), the same curve
// when δ' = δ/(1 − γ) (Mallet's δ = 0.01 is their 0.02 in 2AFC). docs/researchers.md, "QUEST
// and the staircase beside PsychoPy's", has the other conventions.
//
// The scale (QuestScale) is the axis the grid, the prior and the placement live on: the
// difference in % (linear, Mallet's default), or its log10 (QUEST's own "log intensity",
// PsychoPy's). On log10 the Weibull is the same curve ((x/T)^β = 10^(β·(log10 x − log10 T)),
// PsychoPy's form); the logistic is one in log10 x, its β per log10 unit.
//
// Like the staircase, its state is a function of the answers alone, so a resumed session
// replays its rows.
#include <vector>

#include "core/enum_names.hpp"

namespace mallet::study {

enum class QuestShape { weibull, logistic };

//! The axis of the grid, the prior and the placement: the difference in %, or log10 of it.
enum class QuestScale { linear, log10 };
inline constexpr EnumNames<QuestScale, 2> kQuestScaleNames{
    {{QuestScale::linear, "linear"}, {QuestScale::log10, "log10"}}};

//! The point of the posterior each trial tests: its mean (King-Smith et al. 1994), its mode
//! (Watson & Pelli 1983), or its `quantile` (Pelli 1987; PsychoPy's QuestHandler default).
enum class QuestPlacement { mean, mode, quantile };
inline constexpr EnumNames<QuestPlacement, 3> kQuestPlacementNames{
    {{QuestPlacement::mean, "mean"}, {QuestPlacement::mode, "mode"}, {QuestPlacement::quantile, "quantile"}}};

struct QuestModel {
  QuestShape shape = QuestShape::weibull;
  double beta = 3.5;    //!< Weibull: the exponent; logistic: the slope per % (per log10 unit on log10)
  double gamma = 0.5;   //!< guessing (2AFC)
  double delta = 0.01;  //!< lapses, answered wrong (Pelli's and PsychoPy's delta: δ/(1 − γ))
  QuestScale scale = QuestScale::linear;
  //! How a trial is placed travels with the model, so that a track is made from the
  //! protocol's model and prior alone.
  QuestPlacement placement = QuestPlacement::mean;
  double quantile = 0.5;  //!< placement = quantile: the posterior's quantile tested (0.5: the median)
};

struct QuestPrior {
  //! The threshold's Gaussian prior, on the model's scale: % (linear) or log10 of % (log10).
  double mean = 20, sd = 15;
  double lo = 0.5, hi = 100;    //!< the thresholds it can be, and the differences it tests (%)
};

//! P(correct) at difference x (%) for threshold T (%), on the model's scale.
double quest_p_correct(const QuestModel& model, double threshold, double x);

class Quest {
 public:
  Quest(QuestModel model, QuestPrior prior, int grid_points = 1000);

  //! The difference to test next (%), within [lo, hi]: the posterior's mean, mode or
  //! quantile on the model's scale.
  double level() const;
  void answer(double x, bool correct);

  //! The posterior's mean (%): on log10, 10 to the mean of log10 T (its geometric mean).
  double mean() const;
  //! The grid's most probable threshold (%).
  double mode() const;
  //! The posterior's SD of T (%), on either scale.
  double sd() const;
  //! The threshold below which the posterior holds `q` (%), interpolated on the model's scale
  //! between the grid's cumulative sums (as Pelli's QuestQuantile).
  double quantile(double q) const;
  //! The posterior's mean and SD in the scale's own units (% or log10 of %).
  double mean_on_scale() const;
  double sd_on_scale() const;
  int trials() const { return trials_; }

 private:
  QuestModel model_;
  QuestPrior prior_;
  std::vector<double> thresholds_;     //!< the grid (%)
  std::vector<double> on_scale_;       //!< the grid on the model's scale (thresholds_ itself when linear)
  std::vector<double> log_posterior_;  //!< up to a constant: sums of logs, no underflow
  int trials_ = 0;
  //! The posterior normalised (weights summing to 1).
  std::vector<double> weights() const;
  //! From the scale to % (the identity when linear).
  double to_pct(double v) const;
};

}  // namespace mallet::study
