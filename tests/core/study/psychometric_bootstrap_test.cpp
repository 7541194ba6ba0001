// The bootstrap's intervals (core/study/psychometric_bootstrap.hpp), checked as a
// statistician would: over many simulated experiments with a known threshold, a 95 %
// interval must contain it about 95 % of the time. A fixed seed makes this a fixed
// computation, not a timing or a flaky test.
#include <random>

#include <gtest/gtest.h>

#include "core/study/psychometric_bootstrap.hpp"

namespace mallet::study {
namespace {

constexpr double kThreshold = 12.0, kSlope = 0.25;  // the simulated observer's tactile_only

std::vector<PsychometricLevel> experiment(std::mt19937_64& rng, int trials_per_level) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PsychometricLevel> levels;
  for (double x = 0; x <= 28; x += 4) {
    PsychometricLevel l{x, trials_per_level, 0};
    for (int k = 0; k < trials_per_level; ++k) l.correct += u(rng) < psychometric_2afc(x, kThreshold, kSlope);
    levels.push_back(l);
  }
  return levels;
}

TEST(PsychometricBootstrap, NewtonsRefitFindsTheGridsMaximumOrLeavesItToTheGrid) {
  // The refits start from the data's own fit: on a resample they must land where the full
  // grid search does; on a step (every answer right above a level, chance below) the
  // maximum is at the slope's bound, which Newton's method leaves to the grid.
  std::mt19937_64 rng(11);
  int converged = 0;
  for (int e = 0; e < 20; ++e) {
    const std::vector<PsychometricLevel> data = experiment(rng, 20), resample = experiment(rng, 20);
    const PsychometricFit near = fit_psychometric_2afc(data), grid = fit_psychometric_2afc(resample);
    const PsychometricFit newton = refit_psychometric_2afc(resample, near);
    if (!newton.ok) continue;
    ++converged;
    EXPECT_NEAR(newton.threshold, grid.threshold, 1e-4 * 28);
    EXPECT_NEAR(newton.slope, grid.slope, 1e-4 * grid.slope);
    EXPECT_GE(newton.log_likelihood, grid.log_likelihood - 1e-9);
  }
  EXPECT_GE(converged, 18) << "resamples of a smooth curve: Newton's method settles";
  const std::vector<PsychometricLevel> step{{0, 20, 10}, {4, 20, 10}, {8, 20, 20}, {12, 20, 20}};
  const PsychometricFit at_bound = fit_psychometric_2afc(step);
  ASSERT_TRUE(at_bound.ok);
  EXPECT_NE(at_bound.reason.find("upper bound"), std::string::npos) << at_bound.reason;
  EXPECT_FALSE(refit_psychometric_2afc(step, at_bound).ok);
}

TEST(PsychometricBootstrap, NinetyFivePercentIntervalsCoverTheTrueThresholdAtCloseToTheNominalRate) {
  std::mt19937_64 rng(20261127);
  constexpr int kExperiments = 200;
  int threshold_covered = 0, slope_covered = 0, fitted = 0;
  for (int e = 0; e < kExperiments; ++e) {
    const std::vector<PsychometricLevel> levels = experiment(rng, 20);  // 160 trials
    const PsychometricFit fit = fit_psychometric_2afc(levels);
    ASSERT_TRUE(fit.ok) << fit.reason;
    const PsychometricIntervals ci = bootstrap_2afc(levels, fit, 200, static_cast<std::uint64_t>(e) + 1);
    ASSERT_TRUE(ci.ok);
    EXPECT_LE(ci.threshold.lo, fit.threshold);
    EXPECT_GE(ci.threshold.hi, fit.threshold);
    ++fitted;
    threshold_covered += ci.threshold.contains(kThreshold);
    slope_covered += ci.slope.contains(kSlope);
  }
  // Nominal 95 %: with 200 experiments its standard error is 1.5 points. Percentile
  // intervals of the parametric bootstrap run a little narrow at 20 trials a level
  // (Wichmann & Hill 2001); 90–99 % is "close", a broken interval is far outside.
  const double threshold_rate = static_cast<double>(threshold_covered) / fitted;
  const double slope_rate = static_cast<double>(slope_covered) / fitted;
  EXPECT_GE(threshold_rate, 0.90);
  EXPECT_LE(threshold_rate, 0.99);
  EXPECT_GE(slope_rate, 0.88);
  EXPECT_LE(slope_rate, 0.99);
  RecordProperty("threshold_coverage", std::to_string(threshold_rate));
  RecordProperty("slope_coverage", std::to_string(slope_rate));
  std::printf("coverage over %d experiments: threshold %.3f, slope %.3f\n", fitted, threshold_rate, slope_rate);
}

TEST(PsychometricBootstrap, MoreTrialsNarrowTheIntervalAndTheSameSeedGivesTheSameOne) {
  std::mt19937_64 rng(7);
  const std::vector<PsychometricLevel> few = experiment(rng, 10), many = experiment(rng, 160);
  const PsychometricFit f_few = fit_psychometric_2afc(few), f_many = fit_psychometric_2afc(many);
  const PsychometricIntervals a = bootstrap_2afc(few, f_few, 300, 1), b = bootstrap_2afc(many, f_many, 300, 1);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_LT((b.threshold.hi - b.threshold.lo) * 2, a.threshold.hi - a.threshold.lo);
  const PsychometricIntervals again = bootstrap_2afc(few, f_few, 300, 1);
  EXPECT_EQ(again.threshold.lo, a.threshold.lo);
  EXPECT_EQ(again.slope.hi, a.slope.hi);
  EXPECT_NE(bootstrap_2afc(few, f_few, 300, 2).threshold.lo, a.threshold.lo);
}

TEST(PsychometricBootstrap, NoIntervalWithoutAFitOrWithTooFewResamples) {
  std::mt19937_64 rng(3);
  const std::vector<PsychometricLevel> levels = experiment(rng, 20);
  PsychometricFit none;
  EXPECT_FALSE(bootstrap_2afc(levels, none, 500, 1).ok);
  EXPECT_FALSE(bootstrap_2afc(levels, fit_psychometric_2afc(levels), 10, 1).ok);
}

}  // namespace
}  // namespace mallet::study
