// The simulated observer that lets a whole protocol run headless: deterministic per
// participant and trial, at chance without any feedback, better with more of it.
#include <map>

#include <gtest/gtest.h>

#include "core/study/psychometric_fit.hpp"
#include "core/study/simulated_observer.hpp"
#include "core/study/study_fixture.hpp"

namespace mallet::study {
namespace {

TEST(SimulatedObserver, SameTrialSameAnswerAndChanceWithoutFeedback) {
  StudyProtocol p = test::parse_protocol(test::kTwoAfcProtocol);
  p.repetitions = 400;  // enough trials for the proportions to settle
  const std::vector<ScheduledTrial> schedule = balanced_schedule(p, "P01");
  const SimulatedObserver observer(p, "P01");
  std::map<StudyCondition, std::pair<int, int>> score;  // correct, trials
  for (const ScheduledTrial& t : schedule) {
    const ObserverAnswer a = observer.respond(t);
    EXPECT_EQ(a.answer, observer.respond(t).answer);
    EXPECT_GE(a.response_time, 400'000'000);
    EXPECT_LE(a.response_time, 1'000'000'000);
    auto& [correct, trials] = score[t.condition];
    correct += a.answer == correct_answer(p, t) ? 1 : 0;
    ++trials;
  }
  auto accuracy = [&](StudyCondition c) { return static_cast<double>(score[c].first) / score[c].second; };
  EXPECT_NEAR(accuracy(StudyCondition::none), 0.5, 0.05);
  // Pairs differ by 10 % and 12.5 % in B: P = 0.5 + 0.5·σ(0.25·(x − T)).
  const double both = 0.5 * (psychometric_2afc(10, 8, 0.25) + psychometric_2afc(12.5, 8, 0.25));
  const double visual = 0.5 * (psychometric_2afc(10, 20, 0.25) + psychometric_2afc(12.5, 20, 0.25));
  EXPECT_NEAR(accuracy(StudyCondition::both), both, 0.05);
  EXPECT_NEAR(accuracy(StudyCondition::visual_only), visual, 0.05);
  EXPECT_GT(accuracy(StudyCondition::both), accuracy(StudyCondition::tactile_only));
  EXPECT_GT(accuracy(StudyCondition::tactile_only), accuracy(StudyCondition::visual_only));
}

}  // namespace
}  // namespace mallet::study
