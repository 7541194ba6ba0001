// The summary's numbers on synthetic results with a known answer.
#include <cmath>

#include <gtest/gtest.h>

#include "core/study/study_summary.hpp"

namespace mallet::study {
namespace {

TEST(PsychometricFit, RecoversAKnownCurveFromExpectedCounts) {
  // Counts exactly as the curve predicts (10 000 trials a level): the maximum-likelihood
  // fit must give back the curve's own threshold and slope.
  const double threshold = 12.0, slope = 0.3;
  std::vector<PsychometricLevel> levels;
  for (double x : {2.0, 5.0, 10.0, 15.0, 20.0, 30.0}) {
    const int n = 10000;
    levels.push_back({x, n, static_cast<int>(std::lround(n * psychometric_2afc(x, threshold, slope)))});
  }
  const PsychometricFit f = fit_psychometric_2afc(levels);
  ASSERT_TRUE(f.ok) << f.reason;
  EXPECT_TRUE(f.reason.empty()) << f.reason;
  EXPECT_EQ(f.levels, 6);
  EXPECT_NEAR(f.threshold, threshold, 0.02);
  EXPECT_NEAR(f.slope, slope, 0.003);
}

TEST(PsychometricFit, SaysSoWhenThereAreTooFewLevels) {
  const PsychometricFit f = fit_psychometric_2afc({{5, 10, 6}, {15, 10, 9}, {15, 4, 4}});
  EXPECT_FALSE(f.ok);
  EXPECT_EQ(f.levels, 2);
  EXPECT_EQ(f.reason, "not enough levels (2 distinct stimulus differences; a fit needs 3)");
}

TEST(PsychometricFit, ChanceEverywhereHasNoThresholdInRange) {
  const PsychometricFit f = fit_psychometric_2afc({{5, 100, 50}, {10, 100, 50}, {20, 100, 50}});
  ASSERT_TRUE(f.ok);
  EXPECT_FALSE(f.has_threshold()) << f.threshold;
  EXPECT_NE(f.reason.find("no "), std::string::npos) << f.reason;  // "no estimate" or "no threshold"
}

ResultRow row(const std::string& who, const std::string& condition, double x, bool correct, double rt) {
  ResultRow r;
  r.participant = who;
  r.condition = condition;
  r.difference_pct = x;
  r.correct = correct;
  r.response_time_ms = rt;
  r.source = "file";
  return r;
}

TEST(StudySummary, PerConditionAccuracyCountsAndOrder) {
  std::vector<ResultRow> rows;
  // none: 1 of 4; both: 3 of 4; visual_only: 2 of 2 (one participant each way)
  for (int i = 0; i < 4; ++i) rows.push_back(row("P01", "none", 5.0 * (i + 1), i == 0, 1000));
  for (int i = 0; i < 4; ++i) rows.push_back(row("P02", "both", 5.0 * (i + 1), i != 0, 500));
  rows.push_back(row("P01", "visual_only", 5, true, 600));
  rows.push_back(row("P02", "visual_only", 5, true, 800));
  const StudySummary s = summarize(rows);
  EXPECT_EQ(s.rows, 10);
  EXPECT_EQ(s.participants.size(), 2u);
  ASSERT_EQ(s.conditions.size(), 3u);
  EXPECT_EQ(s.conditions[0].condition, "visual_only");  // the paper's order, not the file's
  EXPECT_EQ(s.conditions[1].condition, "both");
  EXPECT_EQ(s.conditions[2].condition, "none");
  EXPECT_EQ(s.conditions[0].trials, 2);
  EXPECT_DOUBLE_EQ(s.conditions[0].accuracy(), 1.0);
  EXPECT_DOUBLE_EQ(s.conditions[0].mean_response_ms, 700.0);
  EXPECT_DOUBLE_EQ(s.conditions[1].accuracy(), 0.75);
  EXPECT_DOUBLE_EQ(s.conditions[2].accuracy(), 0.25);
  ASSERT_TRUE(s.conditions[0].fit);
  EXPECT_FALSE(s.conditions[0].fit->ok);  // one level
  ASSERT_TRUE(s.conditions[1].fit);
  EXPECT_TRUE(s.conditions[1].fit->ok);   // four levels

  const StudySummary only = summarize(rows, "P01");
  EXPECT_EQ(only.rows, 5);
  ASSERT_EQ(only.conditions.size(), 2u);

  const std::string text = format_summary(s);
  EXPECT_NE(text.find("visual_only          2        2    100.0%      700.0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("none                 4        1     25.0%     1000.0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("not enough levels (1 distinct stimulus difference; a fit needs 3)"), std::string::npos) << text;
}

TEST(StudySummary, VisitorSessionsAreCompletedWhenTheirRowsReachTheirPlannedTrials) {
  std::vector<ResultRow> rows;
  const auto add = [&](const std::string& who, int n, int planned) {
    for (int t = 1; t <= n; ++t) {
      ResultRow r = row(who, "both", 10, true, 500);
      r.trial = t;
      r.planned_trials = planned;
      rows.push_back(r);
    }
  };
  add("visitor-00000001", 6, 6);
  add("visitor-00000002", 2, 6);  // walked away
  add("visitor-00000003", 6, 6);
  add("P01", 3, 32);  // a lab participant who stopped early is not a visitor
  const StudySummary s = summarize(rows);
  EXPECT_EQ(s.visitor_sessions_completed, 2);
  EXPECT_EQ(s.visitor_sessions_abandoned, 1);
  EXPECT_NE(format_summary(s).find("visitor sessions: 3 (2 completed, 1 abandoned)\n"), std::string::npos)
      << format_summary(s);
  const std::vector<ResultRow> lab(rows.end() - 3, rows.end());
  EXPECT_EQ(format_summary(summarize(lab)).find("visitor sessions"), std::string::npos) << "only when there are any";
  rows.resize(3);  // the first visitor's first 3 of 6 trials
  EXPECT_EQ(summarize(rows).visitor_sessions_abandoned, 1);
}

TEST(StudySummary, NamingRowsHaveNoFit) {
  std::vector<ResultRow> rows{row("P01", "both", std::nan(""), true, 500)};
  const StudySummary s = summarize(rows);
  ASSERT_EQ(s.conditions.size(), 1u);
  EXPECT_FALSE(s.conditions[0].fit);
  EXPECT_EQ(format_summary(s).find("psychometric"), std::string::npos);
}

}  // namespace
}  // namespace mallet::study
