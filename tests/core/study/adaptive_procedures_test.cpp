// The adaptive procedures (core/study/staircase.hpp, quest.hpp) against simulated observers
// whose threshold is known: over many seeded runs their estimates converge where theory
// puts them, within stated bounds. Fixed seeds: a computation, not a timing or flaky test.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/study/psychometric_fit.hpp"
#include "core/study/quest.hpp"
#include "core/study/staircase.hpp"

namespace mallet::study {
namespace {

constexpr double kThreshold = 12.0, kSlope = 0.25;  // the simulated observer's tactile_only
constexpr int kRuns = 200;

//! The difference at which the observer is correct with probability p (its curve inverted).
double observer_at(double p) { return kThreshold - std::log(0.5 / (p - 0.5) - 1.0) / kSlope; }

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
    while (!s.done()) s.answer(u(rng) < psychometric_2afc(s.level(), kThreshold, kSlope));
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
  logistic.beta = kSlope;
  logistic.delta = 0;
  EXPECT_DOUBLE_EQ(quest_p_correct(logistic, kThreshold, 20.0), psychometric_2afc(20.0, kThreshold, kSlope));
  Quest q(logistic, QuestPrior{20, 10, 0.5, 60});
  const double prior_sd = q.sd();
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int t = 0; t < 200; ++t) {
    const double x = q.level();
    q.answer(x, u(rng) < psychometric_2afc(x, kThreshold, kSlope));
  }
  EXPECT_LT(q.sd(), prior_sd / 3);
  EXPECT_NEAR(q.mean(), kThreshold, 3 * q.sd() + 0.5);
  EXPECT_NEAR(q.mode(), q.mean(), q.sd());
}

}  // namespace
}  // namespace mallet::study
