// An adaptive protocol's trials (core/study/adaptive_schedule.hpp): interleaved tracks, one
// per condition, each testing its own level on the protocol's grid, ending by their own
// rules, and the same again when the answers are replayed (a resumed session).
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "core/study/adaptive_schedule.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/study/psychometric_fit.hpp"
#include "core/study/simulated_observer.hpp"
#include "core/study/study_fixture.hpp"

namespace mallet::study {
namespace {

StudyProtocol shipped(const char* file) {
  return load_study_protocol(test::config_dir() / "study" / file, test::percussion().materials,
                             test::percussion().targets.size());
}

//! Runs the tracks to their end with the simulated observer; the trials and answers.
std::vector<std::pair<ScheduledTrial, bool>> run(const StudyProtocol& p, const std::string& who) {
  AdaptiveSchedule s(p, who);
  const SimulatedObserver observer(p, who);
  std::vector<std::pair<ScheduledTrial, bool>> out;
  while (const std::optional<ScheduledTrial> t = s.next()) {
    const bool correct = observer.respond(*t).answer == correct_answer(p, *t);
    out.emplace_back(*t, correct);
    s.record(*t, correct);
    EXPECT_LE(static_cast<int>(out.size()), s.max_trials());
  }
  return out;
}

TEST(AdaptiveSchedule, StaircaseTracksInterleaveAndEachSettlesNearItsObserversTarget) {
  const StudyProtocol p = shipped("staircase.toml");
  const auto trials = run(p, "P01");
  std::map<StudyCondition, int> per_condition;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    ++per_condition[trials[i].first.condition];
    EXPECT_EQ(trials[i].first.number, static_cast<int>(i + 1));
  }
  EXPECT_EQ(per_condition.size(), 3u) << "every condition's track ran";
  // Interleaved: within the first 12 trials at least two conditions.
  std::map<StudyCondition, int> early;
  for (std::size_t i = 0; i < 12; ++i) ++early[trials[i].first.condition];
  EXPECT_GE(early.size(), 2u);
  // Replayed: the state after the answers is the state the tracks reached.
  AdaptiveSchedule replay(p, "P01");
  for (const auto& [t, correct] : trials) {
    const std::optional<ScheduledTrial> again = replay.next();
    ASSERT_TRUE(again);
    EXPECT_EQ(again->condition, t.condition);
    EXPECT_EQ(again->item, t.item);
    EXPECT_EQ(again->swapped, t.swapped);
    replay.record(*again, correct);
  }
  EXPECT_FALSE(replay.next()) << "every track is done";
  // Each track's estimate lies near its 70.7 % point (the observer's 75 % thresholds are 20,
  // 12 and 8 %, slope 0.25/%: 70.7 % correct 1.39 % below them) and keeps their order.
  const double below = std::log(0.5 / (staircase_target(2) - 0.5) - 1.0) / SimulatedObserver::kSlopePerPct;
  std::map<StudyCondition, double> estimate;
  for (StudyCondition c : p.conditions) {
    const TrackState s = replay.state(c);
    EXPECT_TRUE(s.done);
    ASSERT_TRUE(s.estimate_pct) << condition_name(c);
    estimate[c] = *s.estimate_pct;
    EXPECT_NEAR(*s.estimate_pct, SimulatedObserver::threshold_pct(c) - below, 5.0) << condition_name(c);
  }
  EXPECT_LT(estimate[StudyCondition::both], estimate[StudyCondition::visual_only]);
}

TEST(AdaptiveSchedule, QuestTracksTestTheirPosteriorsMeanOnTheGridAndStopAtTheirCount) {
  const StudyProtocol p = shipped("quest.toml");
  const auto trials = run(p, "P02");
  EXPECT_EQ(trials.size(), 40u * 3);
  AdaptiveSchedule s(p, "P02");
  double first_sd = 0;
  for (const auto& [t, correct] : trials) {
    if (t.number == 1) first_sd = s.state(t.condition).estimate_sd_pct.value_or(0);
    // What a trial tests is on the grid: a pair's difference, the nearest to the track's level.
    const double tested = p.pairs.at(static_cast<std::size_t>(t.item)).difference_pct;
    EXPECT_EQ(tested, s.state(t.condition).level_pct);
    s.record(t, correct);
  }
  for (StudyCondition c : p.conditions) {
    const TrackState st = s.state(c);
    EXPECT_EQ(st.trials, 40);
    ASSERT_TRUE(st.estimate_sd_pct);
    EXPECT_LT(*st.estimate_sd_pct, first_sd / 2) << "the posterior narrows";
  }
}


TEST(AdaptiveSchedule, QuestPlusTracksConvergeOnTheObserversThresholdsAndReplayAlike) {
  // The shipped QUEST+ protocol: a logistic at criterion 0.75, the simulated observer's own
  // curve (thresholds 20, 12 and 8 %, slope 0.25 per %, no lapses), 64 trials a condition.
  const StudyProtocol p = shipped("quest_plus.toml");
  ASSERT_EQ(p.procedure, StudyProcedure::quest_plus);
  const auto trials = run(p, "P03");
  EXPECT_EQ(trials.size(), 64u * 3);
  AdaptiveSchedule replay(p, "P03");
  EXPECT_EQ(replay.max_trials(), 64 * 3);
  for (const auto& [t, correct] : trials) {
    const std::optional<ScheduledTrial> again = replay.next();
    ASSERT_TRUE(again);
    EXPECT_EQ(again->condition, t.condition);
    EXPECT_EQ(again->item, t.item);
    // What a trial tests is the track's level itself: QUEST+ chooses among the pairs.
    EXPECT_EQ(p.pairs.at(static_cast<std::size_t>(t.item)).difference_pct, replay.state(t.condition).level_pct);
    replay.record(*again, correct);
  }
  EXPECT_FALSE(replay.next()) << "every track is done";
  std::map<StudyCondition, double> estimate;
  for (StudyCondition c : p.conditions) {
    const TrackState s = replay.state(c);
    EXPECT_TRUE(s.done);
    EXPECT_EQ(s.trials, 64);
    EXPECT_EQ(s.reversals, -1);
    ASSERT_TRUE(s.estimate_pct && s.estimate_sd_pct) << condition_name(c);
    estimate[c] = *s.estimate_pct;
    EXPECT_NEAR(*s.estimate_pct, SimulatedObserver::threshold_pct(c), 2 * *s.estimate_sd_pct + 1.0)
        << condition_name(c) << " ± " << *s.estimate_sd_pct;
    EXPECT_LT(*s.estimate_sd_pct, 5.0) << condition_name(c);
  }
  EXPECT_LT(estimate[StudyCondition::both], estimate[StudyCondition::visual_only]);
}

}  // namespace
}  // namespace mallet::study
