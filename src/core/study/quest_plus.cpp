#include "core/study/quest_plus.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mallet::study {

namespace {

//! ln ψ tabled for ψ = 0: e^−1000 is 0 in double precision, and it stays finite, so that
//! 0·ln 0 needs no branch in the entropy's inner loop.
constexpr double kLnZero = -1000.0;

double ln_or_floor(double p) { return p > 0 ? std::max(std::log(p), kLnZero) : kLnZero; }

double x_ln_x(double p) { return p > 0 ? p * std::log(p) : 0.0; }

}  // namespace

QuestPlus::QuestPlus(const QuestPlusSetup& setup, std::vector<double> stimuli) : stimuli_(std::move(stimuli)) {
  const QuestPlusGrid& g = setup.grid;
  if (stimuli_.empty() || g.thresholds.empty() || g.slopes.empty() || g.lapses.empty())
    throw std::invalid_argument("QUEST+ needs at least one stimulus and one value of each parameter");
  auto table = std::make_shared<Table>();
  table->grid = g;
  table->params = g.size();
  const std::size_t n = table->params;
  table->p_correct.resize(stimuli_.size() * n);
  table->ln_correct.resize(stimuli_.size() * n);
  table->ln_wrong.resize(stimuli_.size() * n);
  for (std::size_t s = 0; s < stimuli_.size(); ++s) {
    std::size_t i = s * n;
    for (double t : g.thresholds)
      for (double slope : g.slopes)
        for (double lapse : g.lapses) {
          const double p = std::clamp(psychometric_p(setup.model, {t, slope, lapse}, stimuli_[s]), 0.0, 1.0);
          table->p_correct[i] = p;
          table->ln_correct[i] = ln_or_floor(p);
          table->ln_wrong[i] = ln_or_floor(1.0 - p);
          ++i;
        }
  }
  table_ = std::move(table);

  // The prior, up to a constant: uniform, or Gaussian in the threshold alone.
  log_posterior_.assign(n, 0.0);
  if (const auto& prior = setup.threshold_prior) {
    const double sd = prior->sd > 0 ? prior->sd : 1.0;
    const std::size_t per_threshold = g.slopes.size() * g.lapses.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double z = (g.thresholds[i / per_threshold] - prior->mean) / sd;
      log_posterior_[i] = -0.5 * z * z;
    }
  }
  refresh();
}

void QuestPlus::refresh() {
  const std::size_t n = table_->params;
  const double top = *std::max_element(log_posterior_.begin(), log_posterior_.end());
  posterior_.resize(n);
  ln_posterior_.resize(n);
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += posterior_[i] = std::exp(log_posterior_[i] - top);
  const double ln_sum = std::log(sum);
  for (std::size_t i = 0; i < n; ++i) {
    posterior_[i] /= sum;
    ln_posterior_[i] = log_posterior_[i] - top - ln_sum;
  }

  // Watson's expected entropy for every stimulus, with q = π·ψ:
  //   E[H](x) = Σ_r P_r·H_r = Σ_r (P_r ln P_r − Σ_θ q ln q),  ln q = ln π + ln ψ.
  expected_entropy_.resize(stimuli_.size());
  const double* post = posterior_.data();
  const double* ln_post = ln_posterior_.data();
  for (std::size_t s = 0; s < stimuli_.size(); ++s) {
    const double* pc = table_->p_correct.data() + s * n;
    const double* lc = table_->ln_correct.data() + s * n;
    const double* lw = table_->ln_wrong.data() + s * n;
    double p_correct = 0, p_wrong = 0, q_ln_q_correct = 0, q_ln_q_wrong = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double qc = post[i] * pc[i];
      const double qw = post[i] - qc;
      p_correct += qc;
      p_wrong += qw;
      q_ln_q_correct += qc * (ln_post[i] + lc[i]);
      q_ln_q_wrong += qw * (ln_post[i] + lw[i]);
    }
    expected_entropy_[s] = x_ln_x(p_correct) - q_ln_q_correct + x_ln_x(p_wrong) - q_ln_q_wrong;
  }
  next_ = 0;
  for (std::size_t s = 1; s < stimuli_.size(); ++s) {
    const double e = expected_entropy_[s], best = expected_entropy_[next_];
    if (e < best || (e == best && stimuli_[s] < stimuli_[next_])) next_ = s;
  }
}

void QuestPlus::answer(double x, bool correct) {
  std::size_t nearest = 0;
  for (std::size_t s = 1; s < stimuli_.size(); ++s)
    if (std::abs(stimuli_[s] - x) < std::abs(stimuli_[nearest] - x)) nearest = s;
  answer_index(nearest, correct);
}

void QuestPlus::answer_index(std::size_t stimulus, bool correct) {
  if (stimulus >= stimuli_.size()) throw std::out_of_range("QUEST+: no such stimulus");
  ++trials_;
  const std::size_t n = table_->params;
  const double* ln_psi = (correct ? table_->ln_correct : table_->ln_wrong).data() + stimulus * n;
  for (std::size_t i = 0; i < n; ++i) log_posterior_[i] += ln_psi[i];
  refresh();
}

PsychometricParams QuestPlus::params(std::size_t i) const {
  const QuestPlusGrid& g = table_->grid;
  const std::size_t nl = g.lapses.size(), ns = g.slopes.size();
  return {g.thresholds[i / (ns * nl)], g.slopes[(i / nl) % ns], g.lapses[i % nl]};
}

PsychometricParams QuestPlus::mean() const {
  PsychometricParams m{0, 0, 0};
  for (std::size_t i = 0; i < posterior_.size(); ++i) {
    const PsychometricParams p = params(i);
    m.threshold += posterior_[i] * p.threshold;
    m.slope += posterior_[i] * p.slope;
    m.lapse += posterior_[i] * p.lapse;
  }
  return m;
}

PsychometricParams QuestPlus::sd() const {
  const PsychometricParams m = mean();
  PsychometricParams v{0, 0, 0};
  for (std::size_t i = 0; i < posterior_.size(); ++i) {
    const PsychometricParams p = params(i);
    v.threshold += posterior_[i] * (p.threshold - m.threshold) * (p.threshold - m.threshold);
    v.slope += posterior_[i] * (p.slope - m.slope) * (p.slope - m.slope);
    v.lapse += posterior_[i] * (p.lapse - m.lapse) * (p.lapse - m.lapse);
  }
  return {std::sqrt(v.threshold), std::sqrt(v.slope), std::sqrt(v.lapse)};
}

PsychometricParams QuestPlus::mode() const {
  const auto best = std::max_element(log_posterior_.begin(), log_posterior_.end());
  return params(static_cast<std::size_t>(best - log_posterior_.begin()));
}

double QuestPlus::entropy() const {
  double h = 0;
  for (std::size_t i = 0; i < posterior_.size(); ++i)
    if (posterior_[i] > 0) h -= posterior_[i] * ln_posterior_[i];
  return h;
}

}  // namespace mallet::study
