// An adaptive protocol's trials (core/study/adaptive_schedule.hpp): interleaved tracks, one
// per condition, each testing its own level on the protocol's grid, ending by their own
// rules, and the same again when the answers are replayed (a resumed session).
#include <algorithm>
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

//! The trials of a shipped protocol's run as one text: each trial's condition (its index in the
//! protocol), item and answer.
struct RunText {
  std::string conditions, answers;
  std::vector<int> items;
};
RunText as_text(const StudyProtocol& p, const std::vector<std::pair<ScheduledTrial, bool>>& trials) {
  RunText out;
  for (const auto& [t, correct] : trials) {
    const auto c = std::find(p.conditions.begin(), p.conditions.end(), t.condition) - p.conditions.begin();
    out.conditions += static_cast<char>('0' + c);
    out.answers += correct ? '1' : '0';
    out.items.push_back(t.item);
  }
  return out;
}

// The expected values below were printed by the code as it was before step_type,
// initial_one_up_one_down, discard_reversals, QUEST's scale and placement existed (commit
// 55894ce), running the shipped protocols with the simulated observer as run() does; they
// are not derived from the code under test. The shipped protocols, which use none of the new
// keys, must decide exactly as they did: the same trials, the same answers, the same estimates
// bit for bit.
TEST(AdaptiveSchedule, TheShippedProtocolsDecideExactlyAsBeforeTheNewOptions) {
  {
    const StudyProtocol p = shipped("staircase.toml");
    const auto trials = run(p, "P01");
    const RunText text = as_text(p, trials);
    EXPECT_EQ(text.conditions,
              std::string("22021001100201020101211000212212210012111020111100220212002112011110200112022110"
                          "221112001222112022102210002202220"));
    EXPECT_EQ(text.answers,
              std::string("11111111111111110111101100011101110110010010110111111111010110111011101110111110"
                          "111001100001101111110111101110111"));
    const std::vector<int> items{
        59, 59, 59, 43, 59, 59, 43, 59, 43, 43, 27, 43, 27, 43, 11, 27, 11, 27, 19, 27, 27, 11, 19, 19, 15,
        19, 11, 19, 19, 19, 15, 15, 15, 19, 23, 27, 19, 11, 15, 19, 19, 27, 15, 31, 23, 23, 19, 23, 35, 35,
        15, 11, 31, 11, 23, 7, 31, 35, 7, 19, 19, 11, 35, 15, 15, 11, 15, 31, 15, 31, 35, 15, 11, 15, 35, 19,
        19, 11, 7, 31, 15, 15, 7, 3, 7, 11, 35, 35, 11, 11, 15, 19, 15, 15, 19, 39, 15, 15, 19, 39, 11, 15,
        19, 35, 35, 31, 15, 11, 35, 11, 15, 15, 35};
    EXPECT_EQ(text.items, items);
    AdaptiveSchedule s(p, "P01");
    for (const auto& [t, correct] : trials) s.record(t, correct);
    const std::pair<StudyCondition, std::pair<double, int>> expected[] = {
        {StudyCondition::visual_only, {0x1p+4, 36}},
        {StudyCondition::tactile_only, {0x1p+3, 38}},
        {StudyCondition::both, {0x1.8p+2, 39}}};
    for (const auto& [c, level_estimate] : expected) {
      const TrackState st = s.state(c);
      EXPECT_EQ(st.level_pct, level_estimate.first) << condition_name(c);
      EXPECT_EQ(st.reversals, 12) << condition_name(c);
      EXPECT_EQ(st.trials, level_estimate.second) << condition_name(c);
      EXPECT_FALSE(st.estimate_mode_pct) << "a staircase has no mode";
    }
    EXPECT_EQ(*s.state(StudyCondition::visual_only).estimate_pct, 0x1.14p+4);
    EXPECT_EQ(*s.state(StudyCondition::tactile_only).estimate_pct, 0x1.1p+3);
    EXPECT_EQ(*s.state(StudyCondition::both).estimate_pct, 0x1.dp+2);
  }
  {
    const StudyProtocol p = shipped("quest.toml");
    const auto trials = run(p, "P01");
    const RunText text = as_text(p, trials);
    EXPECT_EQ(text.conditions,
              std::string("22021001100201020101211000212212210012111020111100220212002112011110200112022110"
                          "2211120012221120221022120002212200020010"));
    EXPECT_EQ(text.answers,
              std::string("11111111111111110111111101111101110110110110110111111111010110111011101110111111"
                          "1110011000011111111101111011101111111011"));
    const std::vector<int> items{
        44, 39, 44, 35, 44, 39, 35, 39, 35, 30, 26, 30, 23, 30, 20, 26, 17, 26, 28, 23, 23, 20, 17, 26, 24,
        31, 20, 15, 17, 15, 13, 13, 11, 21, 29, 37, 20, 10, 18, 17, 16, 35, 16, 33, 20, 19, 18, 21, 40, 38,
        15, 14, 36, 13, 20, 12, 35, 40, 12, 20, 19, 14, 39, 19, 18, 18, 19, 38, 17, 37, 41, 19, 19, 17, 40,
        20, 19, 18, 18, 39, 18, 18, 18, 17, 18, 17, 38, 37, 19, 17, 19, 22, 21, 20, 21, 40, 20, 20, 20, 39,
        19, 21, 20, 20, 39, 38, 41, 20, 20, 19, 19, 19, 40, 39, 39, 19, 38, 38, 20, 40};
    EXPECT_EQ(text.items, items);
    AdaptiveSchedule s(p, "P01");
    for (const auto& [t, correct] : trials) s.record(t, correct);
    const std::pair<StudyCondition, std::pair<double, double>> expected[] = {
        {StudyCondition::visual_only, {0x1.4067b8522a8b4p+4, 0x1.639abb853bc22p+1}},
        {StudyCondition::tactile_only, {0x1.52b10b8e4d067p+3, 0x1.83a1f8d7fe23cp+0}},
        {StudyCondition::both, {0x1.351d87177d927p+3, 0x1.5a6ed9792d1f1p+0}}};
    for (const auto& [c, mean_sd] : expected) {
      const TrackState st = s.state(c);
      EXPECT_EQ(st.trials, 40) << condition_name(c);
      EXPECT_EQ(*st.estimate_pct, mean_sd.first) << condition_name(c);
      EXPECT_EQ(*st.estimate_sd_pct, mean_sd.second) << condition_name(c);
      ASSERT_TRUE(st.estimate_mode_pct) << "QUEST's mode, now recorded";
      EXPECT_NEAR(*st.estimate_mode_pct, *st.estimate_pct, 2 * *st.estimate_sd_pct) << condition_name(c);
    }
  }
}

}  // namespace
}  // namespace mallet::study
