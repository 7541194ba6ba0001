// Balanced randomisation: every condition × pair equally often and in both orders equally
// often; the same participant always gets the same order, different participants differ.
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "core/study/balanced_schedule.hpp"
#include "core/study/study_fixture.hpp"

namespace mallet::study {
namespace {

TEST(BalancedSchedule, EveryConditionAndPairEquallyOftenInBothOrders) {
  const StudyProtocol p = test::parse_protocol(test::kTwoAfcProtocol);
  for (const char* participant : {"P01", "P02", "someone.else"}) {
    const std::vector<ScheduledTrial> s = balanced_schedule(p, participant);
    ASSERT_EQ(s.size(), 4u * 2u * 4u);
    std::map<std::tuple<StudyCondition, int, bool>, int> counts;
    for (std::size_t i = 0; i < s.size(); ++i) {
      EXPECT_EQ(s[i].number, static_cast<int>(i + 1));
      ++counts[{s[i].condition, s[i].item, s[i].swapped}];
    }
    ASSERT_EQ(counts.size(), 4u * 2u * 2u) << participant;
    for (const auto& [key, n] : counts) EXPECT_EQ(n, 2) << participant;  // 4 repetitions, half per order
  }
}

TEST(BalancedSchedule, SameParticipantSameOrderOthersDiffer) {
  const StudyProtocol p = test::parse_protocol(test::kTwoAfcProtocol);
  auto order = [&](const char* who) {
    std::vector<std::tuple<StudyCondition, int, bool>> out;
    for (const ScheduledTrial& t : balanced_schedule(p, who)) out.emplace_back(t.condition, t.item, t.swapped);
    return out;
  };
  EXPECT_EQ(order("P01"), order("P01"));
  EXPECT_NE(order("P01"), order("P02"));
  EXPECT_NE(order("P01"), order("P10"));
  StudyProtocol other_seed = p;
  other_seed.seed = 43;
  std::vector<std::tuple<StudyCondition, int, bool>> reseeded;
  for (const ScheduledTrial& t : balanced_schedule(other_seed, "P01")) reseeded.emplace_back(t.condition, t.item, t.swapped);
  EXPECT_NE(order("P01"), reseeded);
}

TEST(BalancedSchedule, ScheduleIsPinnedAcrossCompilers) {
  // The generator is ours, not std::shuffle's: this order must never change, or a resumed
  // session would skip the wrong trials.
  const StudyProtocol p = test::parse_protocol(test::kTwoAfcProtocol);
  EXPECT_EQ(participant_seed(42, "P01"), participant_seed(42, "P01"));
  const std::vector<ScheduledTrial> s = balanced_schedule(p, "P01");
  std::string first;
  for (int i = 0; i < 6; ++i) first += stimuli_text(p, s[static_cast<std::size_t>(i)]) + ";";
  EXPECT_EQ(first, "wood_B110|wood;wood_B110|wood;wood_B110|wood;wood|metal;metal|wood;wood|metal;");
}

TEST(BalancedSchedule, CorrectAnswerIsTheIntervalOfTheLargerDecay) {
  const StudyProtocol p = test::parse_protocol(test::kTwoAfcProtocol);
  ASSERT_EQ(p.pairs.size(), 2u);
  EXPECT_EQ(p.pairs[0].harder, 1);  // wood_B110
  EXPECT_NEAR(p.pairs[0].difference_pct, 10.0, 1e-9);
  EXPECT_EQ(p.pairs[1].harder, 2);  // metal: Table 1's B = 9 against wood's 8
  EXPECT_NEAR(p.pairs[1].difference_pct, 12.5, 1e-9);
  ScheduledTrial t{1, StudyCondition::both, 0, false};
  EXPECT_EQ(stimuli_text(p, t), "wood|wood_B110");
  EXPECT_EQ(correct_answer(p, t), "2");
  t.swapped = true;
  EXPECT_EQ(stimuli_text(p, t), "wood_B110|wood");
  EXPECT_EQ(correct_answer(p, t), "1");
}

TEST(SplitMix64, BelowIsUniformEnough) {
  SplitMix64 rng(1);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 30000; ++i) ++counts[rng.below(3)];
  for (int c : counts) EXPECT_NEAR(c, 10000, 400);
}

}  // namespace
}  // namespace mallet::study
