// QUEST+ (core/study/quest_plus.hpp) against the published algorithm's own examples, a
// grid small enough to compute by hand, a simulated observer, and a replayed session.
//
// The reference sequences are Watson's (2017) worked examples as the Python package
// `questplus` (Richard Höchenberger, github.com/hoechenberger/questplus) tests them:
// questplus/tests/test_qp.py at commit 9d29dea133bb57760b227ca2d07fd77bc971ef1c,
// test_threshold (Watson's Example 1, "{1, 1, 2}"), test_threshold_slope (his
// "Implementation" section) and test_threshold_slope_lapse (Example 2, "{1, 3, 2}"): for a
// given list of answers, the stimulus QUEST+ chooses before each trial and the posterior's
// mode at the end. They are quoted here as data; no code of theirs is used.
//
// Their psychometric function is Watson's Weibull on a decibel axis (mQUESTPlus's
// qpPFWeibull, questplus's weibull(scale="dB")):
//   P(correct) = 1 − δ − (1 − γ − δ)·exp(−10^(β(x − t)/20))
// which is, exactly, psychometric_shape's Gumbel: 10^(β(x − t)/20) = exp(β·ln10/20·(x − t)),
// so slope = β·ln10/20 per dB, and the Gumbel's criterion offset ln(−ln(1 − f)) vanishes at
// f = 1 − 1/e, i.e. criterion = γ + (1 − γ)(1 − 1/e) (81.6 % for 2AFC), where F(t) = 1 − 1/e.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "core/study/quest.hpp"
#include "core/study/quest_plus.hpp"

namespace mallet::study {
namespace {

constexpr double kDbSlope = 0.11512925464970229;  // ln 10 / 20: Watson's β per dB → our slope

//! Watson's dB Weibull as psychometric_shape's Gumbel (see the top of the file).
PsychometricModel watson_weibull_db() {
  return {PsychometricShape::gumbel, 0.5, 0.5 + 0.5 * (1.0 - std::exp(-1.0))};
}

//! Watson's examples' domains: stimuli and thresholds −40…0 dB in 1 dB steps.
std::vector<double> decibels() {
  std::vector<double> x;
  for (int db = -40; db <= 0; ++db) x.push_back(db);
  return x;
}

QuestPlusSetup watson_setup(std::vector<double> betas, std::vector<double> lapses) {
  QuestPlusSetup s;
  s.model = watson_weibull_db();
  s.grid.thresholds = decibels();
  for (double beta : betas) s.grid.slopes.push_back(beta * kDbSlope);
  s.grid.lapses = std::move(lapses);
  return s;
}

//! Plays `answers` ('C' correct, 'W' wrong) and checks that before each trial QUEST+ chooses
//! `expected[i]`; returns it for the estimates.
QuestPlus replay_reference(const QuestPlusSetup& setup, const std::vector<int>& expected, std::string_view answers) {
  EXPECT_EQ(expected.size(), answers.size());
  QuestPlus q(setup, decibels());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(q.level(), expected[i]) << "trial " << i + 1;
    q.answer(q.level(), answers[i] == 'C');
  }
  return q;
}

TEST(QuestPlus, TheGumbelAtItsCriterionIsWatsonsDecibelWeibull) {
  const PsychometricModel m = watson_weibull_db();
  for (double t : {-30.0, -20.0, -3.0})
    for (double beta : {2.0, 3.5, 5.0})
      for (double lapse : {0.0, 0.02, 0.04})
        for (double x : {-40.0, -25.0, -20.0, -12.5, 0.0}) {
          const double watson = 1 - lapse - (1 - 0.5 - lapse) * std::exp(-std::pow(10.0, beta * (x - t) / 20));
          EXPECT_NEAR(psychometric_p(m, {t, beta * kDbSlope, lapse}, x), watson, 1e-14)
              << "t " << t << " beta " << beta << " lapse " << lapse << " x " << x;
        }
}

TEST(QuestPlus, ReproducesWatsonsExample1ThresholdAlone) {
  // questplus test_threshold: threshold −40…0 dB, β = 3.5, γ = 0.5, δ = 0.02; mode −20 dB.
  const std::vector<int> expected{-18, -22, -25, -28, -30, -22, -13, -15, -16, -18, -19, -20, -21, -22, -23, -19,
                                  -20, -20, -18, -18, -19, -17, -17, -18, -18, -18, -19, -19, -19, -19, -19, -19};
  const QuestPlus q = replay_reference(watson_setup({3.5}, {0.02}), expected, "CCCCWWCCCCCCCCWCCWCCWCCCCCCCCCCC");
  EXPECT_EQ(q.mode().threshold, -20);
  EXPECT_EQ(q.trials(), 32);
  // Not in the reference: the posterior's mean and SD lie where its mode does.
  EXPECT_NEAR(q.mean().threshold, -20, 1.0);
  EXPECT_LT(q.sd().threshold, 2.0);
  std::printf("Example 1: mode %g dB, mean %.2f dB ± %.2f\n", q.mode().threshold, q.mean().threshold,
              q.sd().threshold);
}

TEST(QuestPlus, ReproducesWatsonsImplementationExampleThresholdAndSlope) {
  // questplus test_threshold_slope: β ∈ {2, 3, 4, 5}; mode −20 dB, β = 3.
  const std::vector<int> expected{
      -18, -22, -12, -13, -15, -16, -17, -18, -19, -21, -24, -25, -26, -27, -21, -22,
      -23, -20, -20, -20, -21, -19, -19, -20, -20, -20, -19, -19, -19, -19, -19, -20,
      -20, -20, -20, -20, -21, -21, -20, -20, -20, -19, -18, -18, -19, -19, -19, -18,
      -18, -17, -18, -18, -18, -17, -17, -17, -17, -17, -17, -17, -18, -18, -18, -18};
  const QuestPlus q = replay_reference(watson_setup({2, 3, 4, 5}, {0.02}), expected,
                                      "CWCCCCCCCCCCCWCCWCCCWCCCCWCCCCCCCCCCCWCCWWCCCCWCWCCCWCCCCCCCCCCC");
  EXPECT_EQ(q.mode().threshold, -20);
  EXPECT_NEAR(q.mode().slope / kDbSlope, 3, 1e-12);
  std::printf("Implementation: mode %g dB, beta %g; mean %.2f dB ± %.2f, beta %.2f ± %.2f\n", q.mode().threshold,
              q.mode().slope / kDbSlope, q.mean().threshold, q.sd().threshold, q.mean().slope / kDbSlope,
              q.sd().slope / kDbSlope);
}

TEST(QuestPlus, ReproducesWatsonsExample2ThresholdSlopeAndLapse) {
  // questplus test_threshold_slope_lapse: β ∈ {2…5}, δ ∈ {0, 0.01, …, 0.04}; mode −20 dB,
  // β = 5, δ = 0.04. Trials 95 and 96 test 0 dB, the lapse's own stimulus.
  const std::vector<int> expected{
      -18, -22, -25, -28, -30, -21, -12, -14, -15, -16, -18, -19, -20, -22, -23, -18,
      -19, -16, -17, -17, -18, -18, -18, -19, -19, -17, -17, -18, -18, -18, -18, -19,
      -19, -20, -18, -18, -18, -18, -18, -19, -19, -19, -19, -20, -18, -18, -18, -18,
      -18, -18, -18, -18, -18, -19, -19, -19, -20, -18, -18, -18, -18, -19, -19, -19,
      -18, -18, -18, -18, -19, -19, -19, -19, -19, -19, -19, -19, -20, -21, -19, -19,
      -19, -19, -19, -19, -19, -18, -19, -19, -16, -16, -16, -16, -16, -16, 0,   0,
      -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -21, -21,
      -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19, -19};
  const QuestPlus q = replay_reference(watson_setup({2, 3, 4, 5}, {0, 0.01, 0.02, 0.03, 0.04}), expected,
                                      "CCCCWWCCCCCCCCWCWCCCCCCCWCCCCCCCCWCCCCCCCCCWCCCWCCCCCCCCWCCCCCCW"
                                      "CCCCCCCCCCCCCWCWCCCCWCCWCCCCCCCWCCCCCCCCCCCCCCCWCCCWCWWCCCCWCCCC");
  const PsychometricParams mode = q.mode();
  EXPECT_EQ(mode.threshold, -20);
  EXPECT_NEAR(mode.slope / kDbSlope, 5, 1e-12);
  EXPECT_EQ(mode.lapse, 0.04);
  const PsychometricParams mean = q.mean(), sd = q.sd();
  std::printf("Example 2: mode %g dB, beta %g, lapse %g; mean %.2f dB ± %.2f, beta %.2f ± %.2f, lapse %.3f ± %.3f\n",
              mode.threshold, mode.slope / kDbSlope, mode.lapse, mean.threshold, sd.threshold,
              mean.slope / kDbSlope, sd.slope / kDbSlope, mean.lapse, sd.lapse);
}

//! −Σ p ln p of a two-valued distribution.
double entropy2(double a, double b) { return -(a * std::log(a) + b * std::log(b)); }

TEST(QuestPlus, ChoosesTheStimulusOfLeastExpectedEntropyOnAGridComputedByHand) {
  // Two thresholds, 0 and 10, equally likely; a logistic so steep (slope 100 per unit) that
  // 10 units from its threshold it is exactly at an asymptote: P = 0.5 below, 1 above, and
  // 0.75 at the threshold (the criterion). No lapses.
  QuestPlusSetup s;
  s.model = {PsychometricShape::logistic, 0.5, 0.75};
  s.grid = {{0, 10}, {100}, {0}};
  QuestPlus q(s, {-10, 0, 10, 20});
  // x = −10: both curves at 0.5; x = 20: both at 1. Either answer leaves the prior: ln 2.
  // x = 0:  P(correct) = (0.75 + 0.5)/2 = 0.625, leaving (0.6, 0.4); P(wrong) = 0.375,
  //         leaving (1/3, 2/3).
  // x = 10: P(correct) = (1 + 0.75)/2 = 0.875, leaving (4/7, 3/7); a wrong answer rules
  //         threshold 0 out, leaving (0, 1) and no entropy.
  const std::vector<double>& e = q.expected_entropies();
  ASSERT_EQ(e.size(), 4u);
  EXPECT_NEAR(e[0], std::log(2.0), 1e-15);
  EXPECT_NEAR(e[1], 0.625 * entropy2(0.6, 0.4) + 0.375 * entropy2(1.0 / 3, 2.0 / 3), 1e-15);  // 0.6593
  EXPECT_NEAR(e[2], 0.875 * entropy2(4.0 / 7, 3.0 / 7), 1e-15);                               // 0.5979
  EXPECT_NEAR(e[3], std::log(2.0), 1e-15);
  EXPECT_NEAR(q.entropy(), std::log(2.0), 1e-15);
  EXPECT_EQ(q.level(), 10);
  // A wrong answer there: threshold 10 is certain.
  q.answer(10, false);
  EXPECT_EQ(q.posterior(), (std::vector<double>{0, 1}));
  EXPECT_EQ(q.mean().threshold, 10);
  EXPECT_EQ(q.sd().threshold, 0);
  EXPECT_EQ(q.mode().threshold, 10);
  EXPECT_EQ(q.entropy(), 0);
}

TEST(QuestPlus, TiesGoToTheSmallestStimulus) {
  // One parameter vector: every stimulus leaves no entropy, so all tie; the smallest x wins
  // whatever the list's order.
  QuestPlusSetup s;
  s.grid = {{5}, {0.3}, {0.02}};
  const QuestPlus q(s, {5, -2, 7, -3});
  EXPECT_EQ(q.level(), -3);
  EXPECT_EQ(q.level_index(), 3u);
}

TEST(QuestPlus, AGaussianPriorOnTheThresholdIsQuestsAndItsUpdatesAreQuestsToo) {
  // With slope and lapse known, a logistic QUEST+ is the logistic QUEST of quest.hpp on the
  // same grid: the same prior, the same likelihoods, hence the same posterior.
  QuestModel qm;
  qm.shape = QuestShape::logistic;
  qm.beta = 0.25;
  qm.delta = 0.02;
  const int points = 120;
  Quest quest(qm, QuestPrior{20, 10, 0.5, 60}, points);
  QuestPlusSetup s;
  s.model = {PsychometricShape::logistic, 0.5, 0.75};
  for (int i = 0; i < points; ++i) s.grid.thresholds.push_back(0.5 + (60 - 0.5) * i / (points - 1));
  s.grid.slopes = {0.25};
  s.grid.lapses = {0.02};
  s.threshold_prior = QuestPlusThresholdPrior{20, 10};
  std::vector<double> stimuli;
  for (int k = 1; k <= 120; ++k) stimuli.push_back(0.5 * k);
  QuestPlus plus(s, stimuli);
  EXPECT_NEAR(plus.mean().threshold, quest.mean(), 1e-9);
  EXPECT_NEAR(plus.sd().threshold, quest.sd(), 1e-9);
  for (int t = 0; t < 30; ++t) {
    const double x = plus.level();
    const bool correct = t % 3 != 2;
    plus.answer(x, correct);
    quest.answer(x, correct);
  }
  EXPECT_NEAR(plus.mean().threshold, quest.mean(), 1e-9);
  EXPECT_NEAR(plus.sd().threshold, quest.sd(), 1e-9);
  EXPECT_EQ(plus.mode().threshold, quest.mode());
}

//! A uniform draw in [0, 1) from 53 bits: the same on every standard library (unlike
//! std::uniform_real_distribution, whose algorithm is left to the implementation).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

TEST(QuestPlus, ItsPosteriorMeanConvergesOnASimulatedObserversThreshold) {
  // A logistic observer (criterion 75 %): threshold 12 %, slope 0.25 per %, 2 % lapses, on
  // a grid of thresholds 1…40 %, slopes {0.1, 0.2, 0.4}, lapses {0, 0.02, 0.04}, testing
  // 1…60 %; 200 trials a run, 20 seeded runs.
  QuestPlusSetup s;
  s.model = {PsychometricShape::logistic, 0.5, 0.75};
  std::vector<double> stimuli;
  for (int k = 1; k <= 60; ++k) stimuli.push_back(k);
  for (int k = 1; k <= 40; ++k) s.grid.thresholds.push_back(k);
  s.grid.slopes = {0.1, 0.2, 0.4};
  s.grid.lapses = {0, 0.02, 0.04};
  const PsychometricParams truth{12, 0.25, 0.02};
  const QuestPlus fresh(s, stimuli);
  const int runs = 20;
  double sum = 0, sum2 = 0, sd_sum = 0;
  int inside = 0;
  for (int r = 0; r < runs; ++r) {
    std::mt19937_64 rng(100 + static_cast<std::uint64_t>(r));
    QuestPlus q = fresh;
    for (int t = 0; t < 200; ++t) q.answer(q.level(), unit(rng) < psychometric_p(s.model, truth, q.level()));
    const double m = q.mean().threshold, sd = q.sd().threshold;
    if (r == 0) {
      EXPECT_NEAR(m, truth.threshold, 3.0) << "the first run alone";
    }
    sum += m;
    sum2 += m * m;
    sd_sum += sd;
    inside += std::abs(m - truth.threshold) <= 2 * sd;
  }
  const double mean = sum / runs, spread = std::sqrt(sum2 / runs - mean * mean);
  // The runs' posterior means centre on the truth within 1 %, scatter by under 3 %, their
  // posterior SDs are under 2.5 % (the uniform prior's is 11.5 %), and honest: the truth lies
  // within two of them in at least 16 of the 20 runs.
  EXPECT_NEAR(mean, truth.threshold, 1.0);
  EXPECT_LT(spread, 3.0);
  EXPECT_LT(sd_sum / runs, 2.5);
  EXPECT_GE(inside, 16);
  std::printf("QUEST+: truth %.1f, posterior means %.2f ± %.2f, mean posterior SD %.2f, %d of %d within 2 SD\n",
              truth.threshold, mean, spread, sd_sum / runs, inside, runs);
}

TEST(QuestPlus, ReplayingTheAnswersGivesTheSameStateAsLivingThem) {
  // What a resumed session does: the rows' answers, replayed into a fresh QUEST+, give the
  // same posterior, bit for bit, and the same next stimulus.
  QuestPlusSetup s = watson_setup({2, 3, 4, 5}, {0, 0.02, 0.04});
  std::mt19937_64 rng(11);
  QuestPlus live(s, decibels());
  std::vector<std::pair<double, bool>> rows;
  for (int t = 0; t < 45; ++t) {
    rows.emplace_back(live.level(), unit(rng) < 0.8);
    live.answer(rows.back().first, rows.back().second);
  }
  QuestPlus replayed(s, decibels());
  for (const auto& [x, correct] : rows) replayed.answer(x, correct);
  EXPECT_EQ(replayed.posterior(), live.posterior());
  EXPECT_EQ(replayed.level(), live.level());
  EXPECT_EQ(replayed.trials(), 45);
  // A copy (one per condition) shares the likelihood table yet keeps its own posterior.
  QuestPlus copy = replayed;
  copy.answer(copy.level(), false);
  EXPECT_EQ(replayed.posterior(), live.posterior());
  EXPECT_NE(copy.posterior(), live.posterior());
}

TEST(QuestPlus, AThousandTrialsNeitherUnderflowNorLoseTheEstimate) {
  // A sharp observer answered 1000 times, then answers only a lapse explains, then (on the
  // hand-computed grid) an answer no vector allows: the posterior stays a finite
  // distribution that sums to 1.
  QuestPlusSetup s;
  s.model = {PsychometricShape::logistic, 0.5, 0.75};
  for (int k = 1; k <= 40; ++k) s.grid.thresholds.push_back(k);
  s.grid.slopes = {0.2, 0.4, 0.8};
  s.grid.lapses = {0, 0.02};
  std::vector<double> stimuli;
  for (int k = 1; k <= 60; ++k) stimuli.push_back(k);
  QuestPlus q(s, stimuli);
  std::mt19937_64 rng(3);
  const PsychometricParams truth{20, 0.4, 0.0};
  for (int t = 0; t < 1000; ++t) q.answer(q.level(), unit(rng) < psychometric_p(s.model, truth, q.level()));
  auto check = [&q](const char* when) {
    double sum = 0;
    for (double p : q.posterior()) {
      ASSERT_TRUE(std::isfinite(p)) << when;
      sum += p;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << when;
    EXPECT_TRUE(std::isfinite(q.mean().threshold) && std::isfinite(q.sd().threshold)) << when;
    EXPECT_TRUE(std::isfinite(q.entropy())) << when;
    for (double e : q.expected_entropies()) EXPECT_TRUE(std::isfinite(e)) << when;
  };
  check("after 1000 trials");
  EXPECT_NEAR(q.mean().threshold, truth.threshold, 1.0);
  EXPECT_EQ(q.mode().threshold, truth.threshold);
  // Ten wrong answers at 60 %, where the lapse-free curves near the truth are at 1.
  for (int t = 0; t < 10; ++t) q.answer(60, false);
  check("after answers only a lapse explains");
  EXPECT_EQ(q.mode().lapse, 0.02);
  EXPECT_EQ(q.trials(), 1010);
  // Both curves of the hand-computed grid are at 1 at x = 20, lapse-free: a wrong answer
  // there rules both out, equally, and they keep comparing as they did.
  QuestPlusSetup steep;
  steep.model = {PsychometricShape::logistic, 0.5, 0.75};
  steep.grid = {{0, 10}, {100}, {0}};
  QuestPlus impossible(steep, {-10, 0, 10, 20});
  impossible.answer(20, false);
  EXPECT_EQ(impossible.posterior(), (std::vector<double>{0.5, 0.5}));
  impossible.answer(0, true);
  EXPECT_NEAR(impossible.posterior()[0], 0.6, 1e-15);
}

}  // namespace
}  // namespace mallet::study
