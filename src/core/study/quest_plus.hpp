#pragma once
// QUEST+ (Watson 2017, "QUEST+: A general multidimensional Bayesian adaptive psychometric
// method", J. Vision 17(3):10): QUEST generalised to several unknown parameters at once. The
// posterior is held on a grid of parameter vectors θ = (threshold, slope, lapse), each a list
// of values (one value: that parameter is known), over the psychometric function of
// psychometric_shape.hpp. Each trial tests, among a fixed list of stimuli x, the one whose
// answer is expected to leave the posterior with the least entropy (Watson's selection rule):
//   P(r | x)      = Σ_θ π(θ)·ψ(r | x, θ)                       (the answer's predicted chance)
//   π'(θ | x, r)  = π(θ)·ψ(r | x, θ) / P(r | x)                 (the posterior it would leave)
//   H(x, r)       = −Σ_θ π'·ln π'                                (its entropy)
//   E[H](x)       = Σ_r P(r | x)·H(x, r)                         (expected over both answers)
// ties going to the smallest x (what mQUESTPlus's MATLAB min and questplus's argmin do, the
// first minimum, on their ascending lists). The answer then multiplies the posterior by its
// likelihood ψ(r | x, θ) (Bayes' rule).
//
// ψ(r | x, θ) is computed once for every stimulus × parameter vector (the likelihood table),
// so a trial costs O(stimuli × parameter vectors) multiply-adds and no logarithm: with
// q = π·ψ, Σ q ln q = Σ q (ln π + ln ψ), and E[H] = Σ_r (P_r ln P_r − Σ_θ q ln q). The
// posterior is held as a sum of logarithms (no underflow however many trials). A vector an
// answer makes impossible (ψ = 0, a lapse-free curve at its asymptote) is ruled out, as the
// reference implementations' zero posterior does: its ln ψ is tabled as −1000, whose exponential is 0 in double precision,
// and if every vector were ruled out they would still compare among themselves.
//
// The estimates are the posterior's mean and SD of each parameter (its marginals) and its
// mode (the joint maximum, the estimate Watson's examples report; ties to the first vector in threshold,
// slope, lapse order). Like Quest and Staircase, its state is a function of the answers alone,
// so a resumed session replays its rows.
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "core/study/psychometric_shape.hpp"

namespace mallet::study {

//! The values each parameter may take (one value: known, not estimated).
struct QuestPlusGrid {
  std::vector<double> thresholds;
  std::vector<double> slopes;
  std::vector<double> lapses{0.0};

  std::size_t size() const { return thresholds.size() * slopes.size() * lapses.size(); }
};

//! A Gaussian prior on the threshold (the existing QUEST's); slope and lapse stay uniform.
struct QuestPlusThresholdPrior {
  double mean = 0, sd = 1;
};

struct QuestPlusSetup {
  PsychometricModel model;  //!< the shape, the guess rate (0.5 for 2AFC) and the criterion
  QuestPlusGrid grid;
  std::optional<QuestPlusThresholdPrior> threshold_prior;  //!< none: uniform over the grid
};

class QuestPlus {
 public:
  //! `stimuli`: the x values it may test (at least one).
  QuestPlus(const QuestPlusSetup& setup, std::vector<double> stimuli);

  //! The stimulus to test next, the one of least expected entropy.
  double level() const { return stimuli_[next_]; }
  std::size_t level_index() const { return next_; }
  //! The answer at `x` (the nearest of the stimuli: the likelihood is tabled for those only).
  void answer(double x, bool correct);
  void answer_index(std::size_t stimulus, bool correct);
  int trials() const { return trials_; }

  //! The posterior's mean of each parameter, its marginal SDs, and its joint mode.
  PsychometricParams mean() const;
  PsychometricParams sd() const;
  PsychometricParams mode() const;

  //! The expected entropy (nats) after a trial at each stimulus, in the stimuli's order.
  const std::vector<double>& expected_entropies() const { return expected_entropy_; }
  //! The posterior's own entropy (nats).
  double entropy() const;
  //! The posterior, normalised, over the grid in threshold, slope, lapse order (lapse fastest).
  const std::vector<double>& posterior() const { return posterior_; }
  const std::vector<double>& stimuli() const { return stimuli_; }
  const QuestPlusGrid& grid() const { return table_->grid; }
  //! The parameter vector of posterior()[i].
  PsychometricParams params(std::size_t i) const;

 private:
  struct Table {
    QuestPlusGrid grid;
    std::size_t params = 0;
    //! Row per stimulus, a column per parameter vector: P(correct), ln P(correct), ln P(wrong).
    std::vector<double> p_correct, ln_correct, ln_wrong;
  };
  std::shared_ptr<const Table> table_;  //!< shared by copies (one per condition's track)
  std::vector<double> stimuli_;
  std::vector<double> log_posterior_;   //!< up to a constant; −∞ where an answer ruled θ out
  std::vector<double> posterior_;       //!< normalised
  std::vector<double> ln_posterior_;    //!< ln of posterior_ (finite where posterior_ > 0)
  std::vector<double> expected_entropy_;
  std::size_t next_ = 0;
  int trials_ = 0;
  //! After the prior or an answer: the normalised posterior and the next stimulus.
  void refresh();
};

}  // namespace mallet::study
