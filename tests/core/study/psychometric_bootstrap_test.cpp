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

TEST(PsychometricBootstrap, TheRefitsClimbEndsWhereTheWholeSearchDoes) {
  // The refits start from the data's own fit and climb with the fit's own method to its
  // precision: on a resample they must land where the whole search does (or hand over to
  // it), to 1e-6 of the range and never lower in likelihood.
  std::mt19937_64 rng(11);
  for (const bool lapse : {false, true}) {
    FitOptions o;
    o.fit_lapse = lapse;
    for (int e = 0; e < 20; ++e) {
      const std::vector<PsychometricLevel> data = experiment(rng, 20), resample = experiment(rng, 20);
      const PsychometricFit near = fit_psychometric(data, o), whole = fit_psychometric(resample, o);
      const PsychometricFit refit = refit_psychometric(resample, o, near);
      ASSERT_TRUE(refit.ok);
      EXPECT_GE(refit.log_likelihood, whole.log_likelihood - 1e-9) << e;
      if (!whole.has_slope()) continue;
      EXPECT_NEAR(refit.threshold, whole.threshold, 1e-6 * 28) << e;
      EXPECT_NEAR(refit.slope, whole.slope, 1e-6 * whole.slope) << e;
    }
  }
  // The data's own counts give the data's own fit, to the last bit: a tie, not a near miss.
  const std::vector<PsychometricLevel> data = experiment(rng, 20);
  const PsychometricFit fit = fit_psychometric_2afc(data);
  EXPECT_EQ(refit_psychometric(data, {}, fit).threshold, fit_psychometric_2afc(data).threshold);
}

//! The share of `experiments` simulated experiments (8 levels × 40 trials from the curve
//! with `lapse`) whose 95 % intervals hold the true threshold and slope.
std::pair<double, double> coverage(const FitOptions& o, double lapse, int experiments, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int threshold_covered = 0, slope_covered = 0;
  for (int e = 0; e < experiments; ++e) {
    std::vector<PsychometricLevel> levels;
    for (double x = 0; x <= 28; x += 4) {
      PsychometricLevel l{x, 40, 0};
      for (int k = 0; k < l.trials; ++k) l.correct += u(rng) < psychometric_p(o.model, {kThreshold, kSlope, lapse}, x);
      levels.push_back(l);
    }
    const PsychometricFit fit = fit_psychometric(levels, o);
    const PsychometricIntervals ci = bootstrap_fit(levels, o, fit, 200, static_cast<std::uint64_t>(e) + 1);
    if (!ci.ok) continue;  // no threshold: counted as not covered
    EXPECT_TRUE(ci.threshold.contains(fit.threshold));
    threshold_covered += ci.threshold.contains(kThreshold);
    slope_covered += ci.slope.contains(kSlope);
  }
  return {static_cast<double>(threshold_covered) / experiments, static_cast<double>(slope_covered) / experiments};
}

// Nominal 95 %: with 400 experiments its standard error is 1.1 points, so 93–97 % is the
// nominal rate within two standard errors. A fixed seed makes each a fixed computation.
constexpr int kExperiments = 400;

TEST(PsychometricBootstrap, NinetyFivePercentIntervalsCoverTheTruthWithTheLapseFixed) {
  const auto [threshold, slope] = coverage({}, 0.0, kExperiments, 20261129);
  std::printf("coverage over %d experiments, lapse fixed at 0: threshold %.4f, slope %.4f\n", kExperiments, threshold,
              slope);
  RecordProperty("threshold_coverage", std::to_string(threshold));
  RecordProperty("slope_coverage", std::to_string(slope));
  for (const double rate : {threshold, slope}) {
    EXPECT_GE(rate, 0.93);
    EXPECT_LE(rate, 0.97);
  }
}

TEST(PsychometricBootstrap, WithTheLapseFittedTheIntervalsRunNarrowByAKnownAmount) {
  // The truth's lapse 0.02, fitted within [0, 0.06]: the percentile intervals run narrow,
  // 89 % and 91.5 % here (93 % and 91.5 % at 80 trials a level). The parametric bootstrap
  // draws from the fitted lapse, which its bound at 0 and the few errors at the top make the
  // least certain parameter (Wichmann & Hill 2001b find the same for small samples); every
  // refit here is the whole search, so it is not a refit missing its maximum. This holds them
  // to that, not to the nominal rate, and docs/researchers.md says so.
  FitOptions fitted;
  fitted.fit_lapse = true;
  const auto [threshold, slope] = coverage(fitted, 0.02, kExperiments, 20261129);
  std::printf("coverage over %d experiments, lapse fitted: threshold %.4f, slope %.4f\n", kExperiments, threshold,
              slope);
  RecordProperty("threshold_coverage", std::to_string(threshold));
  RecordProperty("slope_coverage", std::to_string(slope));
  for (const double rate : {threshold, slope}) {
    EXPECT_GE(rate, 0.87);
    EXPECT_LE(rate, 0.97);
  }
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
