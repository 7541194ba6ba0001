// A trial's state machine on the int64 ns clock.
#include <gtest/gtest.h>

#include "core/study/trial_timeline.hpp"

namespace mallet::study {
namespace {

TEST(TrialTimeline, TwoStimuliThenTheAnswerWindow) {
  StudyTiming timing;  // lead 0.5 s, interval 1.2 s, stimulus 1 s, inter-trial 0.5 s
  const Nanos start = 30 * 86'400 * kNanosPerSecond;  // a month of uptime changes nothing
  TrialTimeline t(timing, start, 2);
  using P = TrialTimeline::Phase;
  EXPECT_EQ(t.phase(start), P::waiting);
  EXPECT_EQ(t.onset(0), start + 500'000'000);
  EXPECT_EQ(t.phase(t.onset(0)), P::stimulus);
  EXPECT_EQ(t.showing(t.onset(0)), 0);
  EXPECT_EQ(t.phase(t.onset(0) + 1'000'000'000), P::gap);
  EXPECT_EQ(t.onset(1), start + 1'700'000'000);
  EXPECT_EQ(t.showing(t.onset(1) + 1), 1);
  EXPECT_EQ(t.answer_opens(), start + 2'700'000'000);
  EXPECT_EQ(t.phase(t.answer_opens() - 1), P::stimulus);
  EXPECT_EQ(t.phase(t.answer_opens()), P::answer);

  EXPECT_FALSE(t.answer(t.answer_opens() - 1));  // a key during a stimulus is not an answer
  EXPECT_FALSE(t.next_start());
  EXPECT_EQ(t.answer(t.answer_opens() + 640'000'000), 640'000'000);
  EXPECT_FALSE(t.answer(t.answer_opens() + 900'000'000));  // one answer per trial
  EXPECT_EQ(t.response_time(), 640'000'000);
  EXPECT_EQ(t.phase(t.answer_opens() + 640'000'000), P::done);
  EXPECT_EQ(t.next_start(), t.answer_opens() + 640'000'000 + 500'000'000);
}

TEST(TrialTimeline, OneStimulusForNamingTheMaterial) {
  TrialTimeline t(StudyTiming{}, 0, 1);
  EXPECT_EQ(t.answer_opens(), 1'500'000'000);
  EXPECT_EQ(t.answer(1'500'000'000), 0);
}

}  // namespace
}  // namespace mallet::study
