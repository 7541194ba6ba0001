// The frame budget's grid: frames no faster than max_fps, no drift, no burst after a late frame.
#include "core/frame_pacer.hpp"

#include <gtest/gtest.h>

namespace mallet {
namespace {

constexpr Nanos kMs = 1'000'000;

TEST(FramePacer, FramesThatComeFasterWaitForTheirSlotOnAGridThatDoesNotDrift) {
  FramePacer p(60.0);
  EXPECT_EQ(p.period_ns(), 16'666'667);
  Nanos t = 1'000 * kMs;
  const Nanos first = p.begin(t);
  EXPECT_EQ(first, t);  // the first frame begins at once
  // A frame costs 2 ms: each waits for its slot, and after a day of frames the slots are
  // still whole periods from the first (the int64 grid does not drift).
  Nanos at = first;
  for (int i = 1; i <= 60 * 60 * 24; ++i) {
    at = p.begin(at + 2 * kMs);
    ASSERT_EQ(at, first + i * p.period_ns()) << i;
  }
}

TEST(FramePacer, ALateFrameIsNotMadeUpForByABurstAndAVeryLateOneRestartsTheGrid) {
  FramePacer p(50.0);  // 20 ms
  EXPECT_EQ(p.begin(0), 0);
  EXPECT_EQ(p.begin(5 * kMs), 20 * kMs);  // early: waits
  EXPECT_EQ(p.begin(47 * kMs), 47 * kMs);  // 7 ms late for the 40 ms slot: begins at once...
  EXPECT_EQ(p.begin(48 * kMs), 60 * kMs);  // ...and the next keeps the grid: no burst
  EXPECT_EQ(p.begin(200 * kMs), 200 * kMs);  // over a whole period late: a new grid from here
  EXPECT_EQ(p.begin(201 * kMs), 220 * kMs);
}

TEST(FramePacer, NoCapLetsEveryFrameBeginAtOnce) {
  FramePacer p;
  EXPECT_EQ(p.begin(123), 123);
  EXPECT_EQ(p.begin(124), 124);
  p.set_max_fps(-3);
  EXPECT_EQ(p.max_fps(), 0.0);
  EXPECT_EQ(p.begin(125), 125);
}

}  // namespace
}  // namespace mallet
