// The fit on the data that short sessions give every day, each case reproduced from the
// shipped protocols (`mallet study --protocol … --headless`, the simulated observer):
// the counts below are those sessions' rows, level by level. A maximum on the search's edge
// is never an estimate, an interval holds its estimate and never leaves what the quantity
// can be, and every reported fit is the likelihood's maximum, checked against a dense grid.
#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "core/study/psychometric_bootstrap.hpp"
#include "core/study/study_summary.hpp"

namespace mallet::study {
namespace {

// config/study/example.toml, participant P01 (2 trials a level).
const std::vector<PsychometricLevel> kP01VisualOnly{{5, 2, 1}, {12.5, 2, 0}, {15, 2, 2}, {30, 2, 2}};
const std::vector<PsychometricLevel> kP01Both{{5, 2, 2}, {12.5, 2, 2}, {15, 2, 2}, {30, 2, 2}};
// docs/study-example/group.toml (12 trials a level): S01 tactile_only, S04 both, and the
// eight participants' `none` pooled.
const std::vector<PsychometricLevel> kS01TactileOnly{{5, 12, 4},   {10, 12, 8},  {15, 12, 8}, {20, 12, 12},
                                                     {25, 12, 12}, {30, 12, 12}, {40, 12, 12}};
const std::vector<PsychometricLevel> kS04Both{{5, 12, 9},   {10, 12, 12}, {15, 12, 8}, {20, 12, 11},
                                              {25, 12, 12}, {30, 12, 12}, {40, 12, 12}};
const std::vector<PsychometricLevel> kPooledNone{{5, 96, 51},  {10, 96, 51}, {15, 96, 53}, {20, 96, 50},
                                                 {25, 96, 50}, {30, 96, 50}, {40, 96, 50}};

//! The summary of `levels` as `mallet study summary` makes it (one participant, one condition).
StudySummary summary_of(const std::vector<PsychometricLevel>& levels, const std::string& condition, int resamples,
                        const FitOptions& fit = {}) {
  std::vector<ResultRow> rows;
  for (const PsychometricLevel& l : levels)
    for (int k = 0; k < l.trials; ++k) {
      ResultRow r;
      r.participant = "P01";
      r.condition = condition;
      r.difference_pct = l.x;
      r.correct = k < l.correct;
      r.response_time_ms = 500;
      rows.push_back(r);
    }
  SummaryOptions options;
  options.resamples = resamples;
  options.fit = fit;
  return summarize(rows, {}, options);
}

//! The highest log-likelihood on a dense grid over the fit's own box.
double dense_grid_maximum(const std::vector<PsychometricLevel>& levels, const FitOptions& o, const FitBox& box,
                          int points = 241, int lapses = 7) {
  double best = -1e300;
  const int nl = o.fit_lapse ? lapses : 1;
  for (int i = 0; i < points; ++i)
    for (int j = 0; j < points; ++j)
      for (int k = 0; k < nl; ++k) {
        const double t = box.threshold_lo + (box.threshold_hi - box.threshold_lo) * i / (points - 1);
        const double s = std::exp(std::log(box.slope_lo) + std::log(box.slope_hi / box.slope_lo) * j / (points - 1));
        const double l = nl == 1 ? box.lapse_lo : box.lapse_lo + (box.lapse_hi - box.lapse_lo) * k / (nl - 1);
        best = std::max(best, psychometric_log_likelihood(levels, o.model, {t, s, l}));
      }
  return best;
}

TEST(HonestFit, AnIntervalHoldsItsOwnEstimate) {
  // Issue case 1: visual_only printed 13.838 with the interval [21.06, 22.71]. A quarter of
  // the resamples repeat the data's counts; their refits are the fit itself, not a point
  // 1e-4 below it, so the bias correction no longer throws the interval onto one tail.
  const StudySummary s = summary_of(kP01VisualOnly, "visual_only", 1000);
  const ConditionSummary& c = s.conditions.at(0);
  ASSERT_TRUE(c.fit->has_threshold()) << c.fit->reason;
  ASSERT_TRUE(c.intervals && c.intervals->ok);
  EXPECT_TRUE(c.intervals->threshold.contains(c.fit->threshold))
      << c.fit->threshold << " [" << c.intervals->threshold.lo << ", " << c.intervals->threshold.hi << "]";
  // The data are a step (answers at 5 and 12.5 % at chance or worse, all right above): the
  // slope is only known to be large, and is printed as such.
  EXPECT_TRUE(c.fit->step);
  EXPECT_NE(c.fit->reason.find("a step: slope at least"), std::string::npos) << c.fit->reason;
  // Whatever the seed, the interval holds the estimate.
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const PsychometricIntervals ci = bootstrap_fit(kP01VisualOnly, {}, *c.fit, 400, seed);
    ASSERT_TRUE(ci.ok);
    EXPECT_TRUE(ci.threshold.contains(c.fit->threshold)) << seed;
  }
}

TEST(HonestFit, AllAnswersCorrectHasNoEstimateAndPrintsNoNumber) {
  // Issue case 2: 8 of 8 correct printed threshold −20.000 [−20.00, −20.00] (the search's
  // edge) and slope 1.1274 [1.265, 1.265].
  const StudySummary s = summary_of(kP01Both, "both", 200);
  const ConditionSummary& c = s.conditions.at(0);
  ASSERT_TRUE(c.fit->ok);
  EXPECT_FALSE(c.fit->has_threshold());
  EXPECT_TRUE(c.fit->threshold_below);
  EXPECT_FALSE(c.intervals.has_value());
  const std::string text = format_summary(s);
  const std::string line = text.substr(text.find("\nboth ", text.find("threshold_pct")) + 1);
  EXPECT_EQ(line.substr(0, line.find('\n')),
            "both                 4              -              -                  -                  -  "
            "threshold below the tested range: no estimate");
}

TEST(HonestFit, TheReportedFitIsTheMaximum) {
  // Issue case 3: S01 tactile_only printed 15.377 / 1.8330 with no note; the maximum in the
  // same range is 15.243 at the slope's bound (log-likelihood −24.2737 against −24.2748).
  const PsychometricFit f = fit_psychometric(kS01TactileOnly);
  ASSERT_TRUE(f.has_threshold()) << f.reason;
  EXPECT_GE(f.log_likelihood, dense_grid_maximum(kS01TactileOnly, {}, f.box, 801) - 1e-9);
  EXPECT_NEAR(f.threshold, 15.243, 0.001);
  EXPECT_NEAR(f.log_likelihood, -24.2737, 1e-4);
  EXPECT_TRUE(f.step);
  EXPECT_FALSE(f.has_slope());
  EXPECT_GT(f.slope_at_least, 0.1);
  EXPECT_LT(f.slope_at_least, f.box.slope_hi);
  EXPECT_NE(f.reason.find("a step: slope at least"), std::string::npos) << f.reason;
}

TEST(HonestFit, AStepsIntervalSpansWhereTheStepMayStand) {
  // Chance at 5 and 10 %, every answer right at 20 and 30 %: the step is somewhere between
  // 10 and 20 %. Every bootstrap refit is the same step at the same place, so the interval
  // comes from the likelihood; it used to be [x, x], zero wide.
  const std::vector<PsychometricLevel> step{{5, 20, 10}, {10, 20, 10}, {20, 20, 20}, {30, 20, 20}};
  const PsychometricFit f = fit_psychometric(step);
  ASSERT_TRUE(f.step && f.has_threshold()) << f.reason;
  EXPECT_GT(f.threshold, 10);
  EXPECT_LT(f.threshold, 20);
  EXPECT_LT(f.step_threshold_lo, 11);
  EXPECT_GT(f.step_threshold_hi, 19);
  const PsychometricIntervals ci = bootstrap_fit(step, {}, f, 200, 1);
  ASSERT_TRUE(ci.ok);
  EXPECT_LE(ci.threshold.lo, f.step_threshold_lo);
  EXPECT_GE(ci.threshold.hi, f.step_threshold_hi);
}

TEST(HonestFit, EveryShapeAndLapseModeFindsTheMaximumOfADenseGrid) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0, 1);
  for (int e = 0; e < 6; ++e) {
    std::vector<PsychometricLevel> levels;
    const double threshold = 8 + 10 * u(rng), slope = 0.1 + 0.5 * u(rng);
    for (double x : {4.0, 8.0, 12.0, 16.0, 24.0, 32.0}) {
      PsychometricLevel l{x, 6 + static_cast<int>(20 * u(rng)), 0};
      for (int k = 0; k < l.trials; ++k) l.correct += u(rng) < 0.01 + 0.98 * psychometric_2afc(x, threshold, slope);
      levels.push_back(l);
    }
    for (const auto& [shape, name] : kPsychometricShapeNames)
      for (const bool lapse : {false, true}) {
        FitOptions o;
        o.model.shape = shape;
        o.fit_lapse = lapse;
        const PsychometricFit f = fit_psychometric(levels, o);
        ASSERT_TRUE(f.ok) << name;
        EXPECT_GE(f.log_likelihood, dense_grid_maximum(levels, o, f.box, 161, 9) - 1e-9)
            << name << (lapse ? " lapse fitted" : "") << " experiment " << e;
      }
  }
}

TEST(HonestFit, TheSearchRangesEdgeIsNotAThreshold) {
  // Issue case 4: the pooled `none` (guessing) printed 75.000 [55.99, 75.00], "extrapolated".
  const StudySummary s = summary_of(kPooledNone, "none", 200);
  const ConditionSummary& c = s.conditions.at(0);
  ASSERT_TRUE(c.fit->ok);
  EXPECT_FALSE(c.fit->has_threshold()) << c.fit->threshold;
  EXPECT_TRUE(c.fit->threshold_above || c.fit->flat) << c.fit->reason;
  EXPECT_EQ(format_summary(s).find("75.000"), std::string::npos) << format_summary(s);
  const std::string table = fit_table_csv(s, {});
  EXPECT_NE(table.find("\nnone,pooled,logistic,0.75,0,7,672,,,,,,,,"), std::string::npos) << table;
}

TEST(HonestFit, AThresholdIntervalNeverGoesBelowZero) {
  // Issue case 5: S04 both printed [−28.00, 13.37] for a difference that cannot be negative.
  const StudySummary s = summary_of(kS04Both, "both", 1000);
  const ConditionSummary& c = s.conditions.at(0);
  ASSERT_TRUE(c.fit->has_threshold()) << c.fit->reason;
  ASSERT_TRUE(c.intervals && c.intervals->ok);
  EXPECT_GE(c.intervals->threshold.lo, 0.0);
  EXPECT_FALSE(c.intervals->threshold.lo_open) << "0 is a limit, not the search's edge";
  EXPECT_TRUE(c.intervals->threshold.contains(c.fit->threshold));
  EXPECT_GE(c.fit->box.threshold_lo, 0.0);
}

TEST(HonestFit, EachShapeRecoversItsOwnCurveWithItsLapse) {
  for (const auto& [shape, name] : kPsychometricShapeNames) {
    FitOptions o;
    o.model.shape = shape;
    o.fit_lapse = true;
    const PsychometricParams truth{14, shape == PsychometricShape::weibull ? 3.0 : 0.3, 0.03};
    std::vector<PsychometricLevel> levels;
    for (double x : {2.0, 6.0, 10.0, 14.0, 18.0, 24.0, 32.0, 48.0}) {
      const int n = 100000;
      levels.push_back({x, n, static_cast<int>(std::lround(n * psychometric_p(o.model, truth, x)))});
    }
    const PsychometricFit f = fit_psychometric(levels, o);
    ASSERT_TRUE(f.has_slope()) << name << ": " << f.reason;
    EXPECT_NEAR(f.threshold, truth.threshold, 0.01) << name;
    EXPECT_NEAR(f.slope, truth.slope, 0.01 * truth.slope) << name;
    EXPECT_NEAR(f.lapse, truth.lapse, 0.001) << name;
    EXPECT_LT(f.deviance, 0.05) << name << ": counts exactly on the curve";
  }
}

TEST(HonestFit, TheCriterionMovesTheThresholdAlongTheSameCurve) {
  // The same data at 75 % and at 80 %: the same curve, so (logistic, 2AFC) the 80 % point
  // lies logit(0.6)/slope above the 75 % one.
  FitOptions at80;
  at80.model.criterion = 0.8;
  const PsychometricFit f75 = fit_psychometric(kS04Both), f80 = fit_psychometric(kS04Both, at80);
  ASSERT_TRUE(f75.has_slope() && f80.has_slope());
  EXPECT_NEAR(f80.slope, f75.slope, 1e-5 * f75.slope);
  EXPECT_NEAR(f80.threshold, f75.threshold + std::log(0.6 / 0.4) / f75.slope, 1e-4);
  EXPECT_NEAR(psychometric_p(at80.model, {f80.threshold, f80.slope, 0}, f80.threshold), 0.8, 1e-12);
}

TEST(HonestFit, DevianceAndResidualsSayWhereTheCurveMisses) {
  // S01 tactile_only: below the step the answers at 10 and 15 % (8 of 12) are above the
  // fitted chance, at 5 % (4 of 12) below it.
  const PsychometricFit f = fit_psychometric(kS01TactileOnly);
  ASSERT_EQ(f.residuals.size(), 7u);
  EXPECT_LT(f.residuals[0], 0);
  EXPECT_GT(f.residuals[1], 0);
  double sum = 0;
  for (double r : f.residuals) sum += r * r;
  EXPECT_NEAR(sum, f.deviance, 1e-9);
  EXPECT_GT(f.deviance, 0);
}

TEST(HonestFit, TheGroupIsEachParticipantsOwnThreshold) {
  std::vector<std::pair<std::string, StudySummary>> participants;
  participants.emplace_back("S01", summary_of(kS01TactileOnly, "tactile_only", 0));
  participants.emplace_back("S04", summary_of(kS04Both, "tactile_only", 0));
  participants.emplace_back("P01", summary_of(kP01Both, "tactile_only", 0));  // no threshold: counted, not used
  const std::vector<GroupThresholds> g = group_thresholds(participants);
  ASSERT_EQ(g.size(), 1u);
  const double a = participants[0].second.conditions[0].fit->threshold;
  const double b = participants[1].second.conditions[0].fit->threshold;
  EXPECT_EQ(g[0].participants, 3);
  EXPECT_EQ(g[0].estimated, 2);
  EXPECT_DOUBLE_EQ(g[0].mean, (a + b) / 2);
  EXPECT_NEAR(g[0].se, std::abs(a - b) / 2, 1e-12);  // SD |a−b|/√2, over √2
  EXPECT_DOUBLE_EQ(g[0].median, (a + b) / 2);
  const std::string text = format_group(g);
  EXPECT_NE(text.find("2 of 3"), std::string::npos) << text;
  EXPECT_NE(text.find("not the pooled fit"), std::string::npos) << text;
}

TEST(HonestFit, TheTableHasOneRowPerFitAndEveryColumn) {
  std::vector<std::pair<std::string, StudySummary>> participants;
  participants.emplace_back("S01", summary_of(kS01TactileOnly, "tactile_only", 100));
  const StudySummary pooled = summary_of(kS01TactileOnly, "tactile_only", 100);
  const std::string table = fit_table_csv(pooled, participants);
  const auto columns = [](const std::string& line) { return std::count(line.begin(), line.end(), ',') + 1; };
  std::vector<std::string> lines;
  for (std::size_t at = 0, next; (next = table.find('\n', at)) != std::string::npos; at = next + 1)
    lines.push_back(table.substr(at, next - at));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], kFitTableColumns);
  EXPECT_EQ(lines[1].rfind("tactile_only,pooled,logistic,0.75,0,7,84,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("tactile_only,S01,", 0), 0u) << lines[2];
  // The note holds "; " but no comma: every row has the header's columns.
  for (const std::string& l : lines) EXPECT_EQ(columns(l), columns(lines[0])) << l;
  EXPECT_NE(lines[1].find(",step,"), std::string::npos) << lines[1];
}

}  // namespace
}  // namespace mallet::study
