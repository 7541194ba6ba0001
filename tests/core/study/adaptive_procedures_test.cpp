// The adaptive procedures (core/study/staircase.hpp, quest.hpp) against simulated observers
// whose threshold is known: over many seeded runs their estimates converge where theory
// puts them, within stated bounds. Fixed seeds: a computation, not a timing or flaky test.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/study/psychometric_fit.hpp"
#include "core/study/quest.hpp"
#include "core/study/staircase.hpp"

namespace mallet::study {
namespace {

constexpr double kObserverThreshold = 12.0, kObserverSlope = 0.25;  // the simulated observer's tactile_only
constexpr int kRuns = 200;

//! The difference at which the observer is correct with probability p (its curve inverted).
double observer_at(double p) { return kObserverThreshold - std::log(0.5 / (p - 0.5) - 1.0) / kObserverSlope; }

struct Spread {
  double mean = 0, sd = 0;
};

Spread staircase_estimates(int down, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sum = 0, sum2 = 0;
  for (int r = 0; r < kRuns; ++r) {
    StaircaseRule rule;
    rule.down = down;
    Staircase s(rule);
    while (!s.done()) s.answer(u(rng) < psychometric_2afc(s.level(), kObserverThreshold, kObserverSlope));
    const std::optional<double> t = s.threshold();
    EXPECT_TRUE(t.has_value()) << "run " << r << ": " << s.reversals() << " reversals in " << s.trials() << " trials";
    sum += *t;
    sum2 += *t * *t;
  }
  const double mean = sum / kRuns;
  return {mean, std::sqrt(sum2 / kRuns - mean * mean)};
}

TEST(Staircase, OneUpTwoDownConvergesOnSeventyOnePercentCorrect) {
  EXPECT_NEAR(staircase_target(2), 0.7071, 1e-4);
  const double target = observer_at(staircase_target(2));  // 10.61 %
  const Spread s = staircase_estimates(2, 1);
  // The mean of 200 runs lies within 1.5 % (of difference) of the 70.7 % point; one run's
  // estimate scatters by under 4 % (8 reversals at a final step of 2 %).
  EXPECT_NEAR(s.mean, target, 1.5) << "target " << target;
  EXPECT_LT(s.sd, 4.0);
  std::printf("1-up-2-down: target %.2f, estimates %.2f ± %.2f over %d runs\n", target, s.mean, s.sd, kRuns);
}

TEST(Staircase, OneUpThreeDownConvergesHigherOnSeventyNinePercent) {
  EXPECT_NEAR(staircase_target(3), 0.7937, 1e-4);
  const double target = observer_at(staircase_target(3));  // 13.41 %
  const Spread s = staircase_estimates(3, 2);
  EXPECT_NEAR(s.mean, target, 1.5) << "target " << target;
  EXPECT_LT(s.sd, 4.0);
  EXPECT_GT(s.mean, staircase_estimates(2, 2).mean) << "a stricter rule settles on a larger difference";
  std::printf("1-up-3-down: target %.2f, estimates %.2f ± %.2f over %d runs\n", target, s.mean, s.sd, kRuns);
}

TEST(Staircase, StepsReversalsAndItsStopFollowTheRule) {
  StaircaseRule rule;
  rule.down = 2;
  rule.start = 30;
  rule.steps = {8, 4};
  rule.stop_reversals = 3;
  rule.threshold_reversals = 2;
  Staircase s(rule);
  s.answer(true);
  EXPECT_EQ(s.level(), 30);  // one correct: no step yet
  s.answer(true);
  EXPECT_EQ(s.level(), 22);  // two: down by 8
  s.answer(false);           // up: a reversal at 22, the step now 4
  EXPECT_EQ(s.reversals(), 1);
  EXPECT_EQ(s.level(), 26);
  s.answer(true);
  s.answer(true);  // down again: a reversal at 26
  EXPECT_EQ(s.level(), 22);
  ASSERT_TRUE(s.threshold().has_value());
  EXPECT_DOUBLE_EQ(*s.threshold(), (22.0 + 26.0) / 2);
  EXPECT_FALSE(s.done());
  s.answer(false);  // the third reversal: done
  EXPECT_TRUE(s.done());
  // Never outside [min, max].
  StaircaseRule low = rule;
  low.start = 1;
  low.min = 0.5;
  Staircase bottom(low);
  for (int i = 0; i < 10; ++i) bottom.answer(true);
  EXPECT_EQ(bottom.level(), 0.5);
}

TEST(Staircase, ReplayingTheAnswersGivesTheSameStateAsLivingThem) {
  // What a resumed session does: the rows' answers, replayed, give the same next level.
  std::mt19937_64 rng(5);
  std::bernoulli_distribution coin(0.7);
  Staircase live(StaircaseRule{});
  std::vector<bool> answers;
  for (int i = 0; i < 37; ++i) {
    answers.push_back(coin(rng));
    live.answer(answers.back());
  }
  Staircase replayed(StaircaseRule{});
  for (bool a : answers) replayed.answer(a);
  EXPECT_EQ(replayed.level(), live.level());
  EXPECT_EQ(replayed.reversal_levels(), live.reversal_levels());
  EXPECT_EQ(replayed.trials(), 37);
}

TEST(Quest, ItsPosteriorConvergesOnAKnownThreshold) {
  // An observer of QUEST's own model (Weibull, β = 3.5, 1 % lapses) with T = 15 %; a prior
  // centred 10 % away with SD 15 %; 40 trials a run.
  const QuestModel model;
  const double truth = 15.0;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sum = 0, sum2 = 0, sd_sum = 0;
  int inside = 0;
  for (int r = 0; r < kRuns; ++r) {
    Quest q(model, QuestPrior{25, 15, 0.5, 100});
    for (int t = 0; t < 40; ++t) {
      const double x = q.level();
      q.answer(x, u(rng) < quest_p_correct(model, truth, x));
    }
    sum += q.mean();
    sum2 += q.mean() * q.mean();
    sd_sum += q.sd();
    inside += std::abs(q.mean() - truth) <= 2 * q.sd();
  }
  const double mean = sum / kRuns, spread = std::sqrt(sum2 / kRuns - mean * mean);
  // The estimates centre on the truth within 1 %, scatter by under 3 %, the posterior's SD
  // shrinks to under a fifth of the prior's, and it is honest: the truth lies within two
  // posterior SDs in at least 90 % of the runs.
  EXPECT_NEAR(mean, truth, 1.0);
  EXPECT_LT(spread, 3.0);
  EXPECT_LT(sd_sum / kRuns, 3.0);
  EXPECT_GE(inside, kRuns * 9 / 10);
  std::printf("QUEST: truth %.1f, posterior means %.2f ± %.2f, mean posterior SD %.2f, %d of %d within 2 SD\n",
              truth, mean, spread, sd_sum / kRuns, inside, kRuns);
}

TEST(Quest, TheLogisticShapeIsTheFitsCurveAndTheModeAndMeanAgreeOnSharpData) {
  QuestModel logistic;
  logistic.shape = QuestShape::logistic;
  logistic.beta = kObserverSlope;
  logistic.delta = 0;
  EXPECT_DOUBLE_EQ(quest_p_correct(logistic, kObserverThreshold, 20.0), psychometric_2afc(20.0, kObserverThreshold, kObserverSlope));
  Quest q(logistic, QuestPrior{20, 10, 0.5, 60});
  const double prior_sd = q.sd();
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int t = 0; t < 200; ++t) {
    const double x = q.level();
    q.answer(x, u(rng) < psychometric_2afc(x, kObserverThreshold, kObserverSlope));
  }
  EXPECT_LT(q.sd(), prior_sd / 3);
  EXPECT_NEAR(q.mean(), kObserverThreshold, 3 * q.sd() + 0.5);
  EXPECT_NEAR(q.mode(), q.mean(), q.sd());
}

// --- PsychoPy's conventions, written down in docs/researchers.md ("QUEST and the staircase
// beside PsychoPy's"), checked here. PsychoPy's formulas are from psychopy/contrib/quest.py
// (QuestObject.recompute, .quantile) and psychopy/data/staircase.py (StairHandler).

//! A uniform draw in [0, 1) from the engine's raw output: the same on every standard library
//! (std::uniform_real_distribution is not).
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1p-53; }

//! PsychoPy's QUEST curve (quest.py's p2, at ε = 0: T the Weibull's scale): a lapse is a blind
//! guess, answered correctly with probability γ; x and T in log10 units.
double psychopy_p2(double delta, double gamma, double beta, double log10_x, double log10_t) {
  return delta * gamma + (1 - delta) * (1 - (1 - gamma) * std::exp(-std::pow(10.0, beta * (log10_x - log10_t))));
}

TEST(Quest, MalletsLapseOfOnePercentIsPsychoPysDeltaOfTwoPercentIn2afc) {
  // Mallet: P = γ + (1 − γ − δ)·W;
  // PsychoPy: P = δ'γ + (1 − δ')(1 − (1 − γ)(1 − W)) = γ + (1 − δ')(1 − γ)·W.
  // The same curve when δ = δ'(1 − γ): δ' = δ/(1 − γ), 0.02 for Mallet's 0.01 at γ = 0.5.
  const QuestModel mallet;  // Weibull, β 3.5, γ 0.5, δ 0.01
  const double t = 12.0;
  for (double x : {0.5, 2.0, 6.0, 10.0, 12.0, 15.0, 25.0, 60.0})
    EXPECT_NEAR(quest_p_correct(mallet, t, x), psychopy_p2(0.02, 0.5, 3.5, std::log10(x), std::log10(t)), 1e-14)
        << "x = " << x;
  // Far above threshold each curve tops out at its own 1 − δ = 1 − δ'(1 − γ).
  EXPECT_NEAR(quest_p_correct(mallet, t, 1e4), 0.99, 1e-12);
  // And PsychoPy's own default, delta = 0.01, is Mallet's 0.005 in 2AFC.
  QuestModel half = mallet;
  half.delta = 0.005;
  EXPECT_NEAR(quest_p_correct(half, t, 9.0), psychopy_p2(0.01, 0.5, 3.5, std::log10(9.0), std::log10(t)), 1e-14);
  // The general relation, at another guessing rate (4AFC, γ = 0.25): δ' = δ/(1 − γ).
  QuestModel four = mallet;
  four.gamma = 0.25;
  four.delta = 0.03;
  for (double x : {3.0, 12.0, 30.0})
    EXPECT_NEAR(quest_p_correct(four, t, x), psychopy_p2(0.03 / 0.75, 0.25, 3.5, std::log10(x), std::log10(t)), 1e-14);
  // On the log10 scale the Weibull is the same curve (PsychoPy's own form).
  QuestModel log = mallet;
  log.scale = QuestScale::log10;
  EXPECT_EQ(quest_p_correct(log, t, 9.0), quest_p_correct(mallet, t, 9.0));
}

TEST(Quest, PsychoPysThresholdIsWherePReachesPThreshold) {
  // PsychoPy shifts its curve by ε so that its threshold is where P = pThreshold (0.82); Mallet's
  // T is the Weibull's scale. T_PsychoPy = T·(−ln(1 − (p − γ)/(1 − γ − δ)))^(1/β), δ Mallet's.
  const QuestModel m;
  const double t = 12.0, p = 0.82;
  const double factor = std::pow(-std::log(1 - (p - m.gamma) / (1 - m.gamma - m.delta)), 1 / m.beta);
  EXPECT_NEAR(quest_p_correct(m, t, t * factor), p, 1e-12);
  EXPECT_NEAR(factor, 1.0164, 1e-4) << "1.6 % above T";
  EXPECT_NEAR(quest_p_correct(m, t, t), 0.5 + 0.49 * (1 - std::exp(-1.0)), 1e-15) << "Mallet's T: 0.81";
}

TEST(Quest, PsychoPysDefaultPlacementIsTheQuantileOfOrderPointFiftyNine) {
  // QuestHandler's method = 'quantile' asks QuestObject.quantile() with no order, which uses the
  // one recompute() works out from the curve's floor pL and ceiling pH (Pelli 1987; for
  // PsychoPy's defaults γ = 0.5, delta = 0.01: pL = 0.5, pH = 0.995). Written out here so the
  // number docs/researchers.md gives (quantile = 0.59 for PsychoPy's default) is checked.
  const double pl = 0.5, ph = 1 - 0.01 * (1 - 0.5);
  const double pe_log =
      ph * std::log(ph) - pl * std::log(pl) + (1 - ph) * std::log(1 - ph) - (1 - pl) * std::log(1 - pl);
  const double pe = 1 / (1 + std::exp(pe_log / (pl - ph)));
  EXPECT_NEAR((pe - pl) / (ph - pl), 0.5898, 1e-4);
}

TEST(Quest, TheDefaultsDecideExactlyAsTheReleaseBeforeScaleAndPlacement) {
  // The expected values below were printed by the code as it was before `scale` and
  // `placement` existed (commit 55894ce, quest.cpp unchanged since), running this same loop;
  // they are not derived from the code under test. The default (linear, mean) must decide bit
  // for bit as it did: the same differences tested, the same posterior.
  const auto run = [](QuestModel model, std::mt19937_64& rng, std::vector<int>& items) {
    Quest q(model, QuestPrior{20, 15, 0.5, 60});  // quest.toml's prior and range
    for (int t = 0; t < 40; ++t) {
      const double k = std::clamp(std::round((q.level() - 0.5) / 0.5), 0.0, 119.0);  // the 0.5 % grid
      const double x = 0.5 + k * 0.5;
      items.push_back(static_cast<int>(k));
      q.answer(x, uniform(rng) < quest_p_correct(model, 12.0, x));
    }
    return q;
  };
  std::mt19937_64 rng(20261127);
  std::vector<int> weibull_items, logistic_items;
  const Quest weibull = run(QuestModel{}, rng, weibull_items);
  EXPECT_EQ(weibull_items, (std::vector<int>{44, 39, 35, 30, 26, 23, 37, 34, 32, 30, 28, 27, 25, 30,
                                             29, 28, 27, 27, 26, 29, 28, 27, 27, 26, 26, 26, 25, 25,
                                             24, 24, 25, 25, 25, 25, 24, 24, 24, 24, 23, 23}));
  EXPECT_EQ(weibull.mean(), 0x1.804c4a07b49e3p+3);
  EXPECT_EQ(weibull.sd(), 0x1.4c0bfe3032066p+0);
  EXPECT_EQ(weibull.mode(), 0x1.764f707f1a64fp+3);
  EXPECT_EQ(weibull.level(), 0x1.804c4a07b49e3p+3);
  QuestModel logistic;
  logistic.shape = QuestShape::logistic;
  logistic.beta = 0.25;
  const Quest l = run(logistic, rng, logistic_items);
  EXPECT_EQ(logistic_items, (std::vector<int>{44, 38, 33, 29, 25, 21, 18, 26, 23, 21, 19, 24, 31, 28,
                                              35, 32, 30, 28, 27, 26, 24, 23, 26, 25, 24, 23, 23, 25,
                                              24, 23, 23, 22, 21, 21, 20, 22, 21, 21, 20, 22}));
  EXPECT_EQ(l.mean(), 0x1.64187e6227d12p+3);
  EXPECT_EQ(l.sd(), 0x1.3abe809a6a45ap+1);
  EXPECT_EQ(l.mode(), 0x1.5d8895a755d89p+3);
}

TEST(Quest, OnTheLog10ScaleThePriorAndThePlacementAreInLog10Units) {
  // A prior of mean log10(10 %) = 1 and SD 0.1 log10 units, far inside [0.5, 60] %: before any
  // answer the mean, median and mode of log10 T are 1 (10 %), its SD 0.1, and the 2.5 % and
  // 97.5 % quantiles 10^(1 ∓ 1.96·0.1) (to the grid's spacing in log10: 0.0021).
  QuestModel model;
  model.scale = QuestScale::log10;
  const QuestPrior prior{1.0, 0.1, 0.5, 60};
  const Quest q(model, prior);
  const double spacing = (std::log10(60.0) - std::log10(0.5)) / 999;
  EXPECT_NEAR(q.mean_on_scale(), 1.0, spacing);
  EXPECT_NEAR(q.sd_on_scale(), 0.1, 1e-3);
  EXPECT_NEAR(std::log10(q.level()), 1.0, spacing);
  EXPECT_NEAR(std::log10(q.quantile(0.5)), 1.0, spacing);
  EXPECT_NEAR(std::log10(q.mode()), 1.0, spacing);
  EXPECT_NEAR(std::log10(q.quantile(0.025)), 1 - 1.959964 * 0.1, spacing);
  EXPECT_NEAR(std::log10(q.quantile(0.975)), 1 + 1.959964 * 0.1, spacing);
  // The mean is the geometric one: 10^E[log10 T], below the arithmetic mean of T (whose SD
  // is what sd() gives, in %).
  EXPECT_NEAR(q.mean(), std::pow(10.0, q.mean_on_scale()), 1e-12);
  const double s2 = std::pow(0.1 * std::log(10.0), 2);  // the variance of ln T
  EXPECT_NEAR(q.sd(), 10 * std::sqrt(std::exp(2 * s2) - std::exp(s2)), 0.01) << "a lognormal's SD";

  // After answers: the placement against a hand computation of the posterior, prior × the
  // likelihood of each answer with PsychoPy's curve (δ' = 2δ), on log10 T: on Quest's own 1000
  // points (every point one weight, as QuestObject's pdf), and as an integral (10⁴ trapezoids).
  QuestModel wide_model = model;
  const QuestPrior wide{std::log10(15.0), 0.4, 0.5, 60};
  Quest answered(wide_model, wide);
  const std::vector<std::pair<double, bool>> answers{{15, true}, {10, true}, {6, false},
                                                      {8, true},  {7, false}, {9, true}};
  for (const auto& [x, correct] : answers) answered.answer(x, correct);
  const auto mean_log10 = [&](int n, bool trapezoids) {
    const double a = std::log10(0.5), b = std::log10(60.0);
    double mass = 0, first = 0;
    for (int i = 0; i <= n; ++i) {
      const double u = a + (b - a) * i / n;
      double p = std::exp(-0.5 * std::pow((u - wide.mean) / wide.sd, 2));
      for (const auto& [x, correct] : answers) {
        const double pc = psychopy_p2(2 * model.delta, 0.5, 3.5, std::log10(x), u);
        p *= correct ? pc : 1 - pc;
      }
      const double weight = trapezoids && (i == 0 || i == n) ? 0.5 : 1.0;
      mass += weight * p;
      first += weight * p * u;
    }
    return first / mass;
  };
  EXPECT_NEAR(answered.mean_on_scale(), mean_log10(999, false), 1e-12);
  EXPECT_NEAR(answered.level(), std::pow(10.0, mean_log10(999, false)), 1e-10);
  // The integral differs by the grid's ends (each a whole point's weight, and the posterior at
  // 60 % is still 0.5 % of its peak): 1.3e-4 log10 units, 0.03 % of the difference.
  EXPECT_NEAR(answered.mean_on_scale(), mean_log10(10000, true), 2e-4);
  // The linear scale with the "same" prior places elsewhere: the scale is not a relabelling.
  Quest linear(QuestModel{}, QuestPrior{15, 6, 0.5, 60});
  for (const auto& [x, correct] : answers) linear.answer(x, correct);
  EXPECT_GT(std::abs(linear.level() - answered.level()), 0.05);
}

TEST(Quest, EachPlacementTestsWhatItSays) {
  QuestModel model;
  const QuestPrior prior{20, 15, 0.5, 60};
  std::mt19937_64 rng(3);
  std::vector<std::pair<double, bool>> answers;
  for (int i = 0; i < 15; ++i) {
    const double x = 4.0 + 2.0 * i;
    answers.emplace_back(x, uniform(rng) < quest_p_correct(model, 12.0, x));
  }
  const auto after = [&](QuestModel m) {
    Quest q(m, prior);
    for (const auto& [x, correct] : answers) q.answer(x, correct);
    return q;
  };
  const Quest by_mean = after(model);
  EXPECT_EQ(by_mean.level(), by_mean.mean());
  QuestModel mode = model;
  mode.placement = QuestPlacement::mode;
  const Quest by_mode = after(mode);
  EXPECT_EQ(by_mode.level(), by_mode.mode());
  QuestModel median = model;
  median.placement = QuestPlacement::quantile;
  median.quantile = 0.5;
  const Quest by_median = after(median);
  EXPECT_EQ(by_median.level(), by_median.quantile(0.5));
  // Quantiles are ordered, and the posterior holds what they say: by the weights' own sums,
  // the 0.59 quantile (PsychoPy's default order) lies between the median and the 0.9 one.
  EXPECT_LT(by_median.quantile(0.1), by_median.quantile(0.5));
  EXPECT_LT(by_median.quantile(0.5), by_median.quantile(0.59));
  EXPECT_LT(by_median.quantile(0.59), by_median.quantile(0.9));
  EXPECT_NEAR(by_median.quantile(0.5), by_median.mean(), by_median.sd()) << "a near-symmetric posterior";
  // The three read the same posterior: only the placement differs.
  EXPECT_EQ(by_mean.mean(), by_mode.mean());
  EXPECT_EQ(by_mean.mode(), by_median.mode());
}

TEST(Staircase, DbAndLogStepsMultiplyTheLevelByTheStatedFactor) {
  EXPECT_DOUBLE_EQ(staircase_step_factor(StaircaseStepType::db, 20), 10.0);  // 20 dB: ×10 (20·log10)
  EXPECT_NEAR(staircase_step_factor(StaircaseStepType::db, 6), 1.99526, 1e-5);  // 6 dB: about ×2
  EXPECT_DOUBLE_EQ(staircase_step_factor(StaircaseStepType::log, 1), 10.0);
  EXPECT_NEAR(staircase_step_factor(StaircaseStepType::log, 0.1), 1.258925, 1e-6);
  StaircaseRule rule;
  rule.down = 1;
  rule.start = 20;
  rule.steps = {6, 3};
  rule.step_type = StaircaseStepType::db;
  Staircase db(rule);
  db.answer(true);  // down 6 dB: divided by 10^(6/20)
  EXPECT_DOUBLE_EQ(db.level(), 20 / std::pow(10.0, 6.0 / 20));
  db.answer(false);  // a reversal; up 3 dB (the step after one reversal)
  EXPECT_DOUBLE_EQ(db.level(), 20 / std::pow(10.0, 6.0 / 20) * std::pow(10.0, 3.0 / 20));
  rule.step_type = StaircaseStepType::log;
  rule.steps = {0.1};
  Staircase log(rule);
  log.answer(false);
  EXPECT_DOUBLE_EQ(log.level(), 20 * std::pow(10.0, 0.1));
  // Multiplying steps never reach zero; they stop at min like any other.
  rule.min = 0.5;
  Staircase bottom(rule);
  for (int i = 0; i < 100; ++i) bottom.answer(true);
  EXPECT_EQ(bottom.level(), 0.5);
}

TEST(Staircase, TheInitialOneUpOneDownPhaseTurnsAtTheFirstWrongAnswer) {
  StaircaseRule rule;
  rule.down = 3;
  rule.start = 30;
  rule.steps = {8, 4};
  rule.initial_one_up_one_down = true;
  Staircase s(rule);
  s.answer(true);
  EXPECT_EQ(s.level(), 22);  // one correct answer is enough before the first reversal
  s.answer(true);
  EXPECT_EQ(s.level(), 14);
  EXPECT_EQ(s.reversals(), 0);
  s.answer(false);  // the first wrong answer: the first reversal, at 14, and up by the next step
  EXPECT_EQ(s.reversals(), 1);
  EXPECT_EQ(s.reversal_levels(), std::vector<double>{14});
  EXPECT_EQ(s.level(), 18);
  s.answer(true);
  s.answer(true);
  EXPECT_EQ(s.level(), 18) << "1-up-3-down from here";
  s.answer(true);
  EXPECT_EQ(s.level(), 14);
  // Without the phase, two correct answers are no step at all.
  rule.initial_one_up_one_down = false;
  Staircase plain(rule);
  plain.answer(true);
  plain.answer(true);
  EXPECT_EQ(plain.level(), 30);
  // Begun wrong, it climbs until the first correct answer, which is the first reversal and
  // steps down at once (the trial that ends the phase still belongs to it, as in StairHandler).
  rule.initial_one_up_one_down = true;
  Staircase climbing(rule);
  climbing.answer(false);
  climbing.answer(false);
  EXPECT_EQ(climbing.level(), 46);
  climbing.answer(true);
  EXPECT_EQ(climbing.reversal_levels(), std::vector<double>{46});
  EXPECT_EQ(climbing.level(), 42);
}

TEST(Staircase, DiscardReversalsNeverCountTheFirstK) {
  // Reversals at 22, 26, 22, 26, 22 (1-up-1-down, steps of 4 after the first): K = 2 of them
  // discarded, N = 2 averaged: an estimate once there are K + N = 4, the mean of the 3rd and 4th.
  StaircaseRule rule;
  rule.down = 1;
  rule.start = 30;
  rule.steps = {8, 4};
  rule.stop_reversals = 20;
  rule.threshold_reversals = 2;
  rule.discard_reversals = 2;
  Staircase s(rule);
  StaircaseRule keep_all = rule;
  keep_all.discard_reversals = 0;
  Staircase all(keep_all);
  const auto both = [&](bool correct) {
    s.answer(correct);
    all.answer(correct);
  };
  both(true);   // 22
  both(false);  // reversal at 22 → 26
  both(true);   // reversal at 26 → 22
  both(false);  // reversal at 22 → 26
  EXPECT_EQ(s.reversals(), 3);
  EXPECT_FALSE(s.threshold()) << "3 reversals: the first 2 do not count, and 1 is not 2";
  ASSERT_TRUE(all.threshold());
  EXPECT_DOUBLE_EQ(*all.threshold(), (26.0 + 22.0) / 2) << "without discarding, the 2nd and 3rd";
  both(true);  // reversal at 26
  EXPECT_EQ(s.reversal_levels(), (std::vector<double>{22, 26, 22, 26}));
  ASSERT_TRUE(s.threshold());
  EXPECT_DOUBLE_EQ(*s.threshold(), (22.0 + 26.0) / 2);  // the 3rd and 4th
  both(false);  // a 5th: the last two, still past the first two
  EXPECT_DOUBLE_EQ(*s.threshold(), (26.0 + 22.0) / 2);
  EXPECT_EQ(*s.threshold(), *all.threshold()) << "with K + N reversals or more, the last N are past the first K";
}

TEST(Staircase, AReversalIsRecordedAtTheDifferenceTested) {
  // Multiplying steps leave the grid: the schedule tests the nearest pair and says so, and the
  // reversal is that difference (StairHandler's addResponse(result, intensity)).
  StaircaseRule rule;
  rule.down = 1;
  rule.start = 20;
  rule.steps = {3};
  rule.step_type = StaircaseStepType::db;
  Staircase s(rule);
  s.answer(true, 20.0);  // → 14.16
  s.answer(false, 14.0);  // a reversal where the trial was: 14 %, not 14.16
  EXPECT_EQ(s.reversal_levels(), std::vector<double>{14.0});
  EXPECT_DOUBLE_EQ(s.level(), 20.0) << "the next level steps from the staircase's own";
}

}  // namespace
}  // namespace mallet::study
