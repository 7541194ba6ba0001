// Choosing the stick's LED among the Wii camera's four IR dots.
#include "core/ir_tracker.hpp"

#include <gtest/gtest.h>

#include <climits>
#include <random>
#include <stdexcept>

namespace mallet {
namespace {

constexpr Nanos kStep = 10'000'000;  // 100 Hz

IrFrame frame(Nanos t, IrSlots slots) { return {t, slots}; }

TEST(IrTracker, AcquiresTheLargestDotThenTheMostCentral) {
  IrTracker tr;
  const IrTrackerUpdate u = tr.update(frame(0, {IrDot{100, 100, 2}, IrDot{800, 600, 5}, std::nullopt, IrDot{500, 400, 3}}));
  ASSERT_TRUE(u.point);
  EXPECT_EQ(u.event, IrTrackerEvent::regained);
  EXPECT_EQ(u.point->slot, 1);
  EXPECT_EQ(u.point->x, 800);
  EXPECT_EQ(u.point->y, 600);
  EXPECT_EQ(u.point->t_ns, 0);
  // Equal sizes (or basic mode, no size): the dot nearest the camera's centre.
  IrTracker basic;
  const IrTrackerUpdate b = basic.update(frame(0, {IrDot{10, 10, -1}, IrDot{520, 380, -1}, IrDot{1000, 700, -1}}));
  ASSERT_TRUE(b.point);
  EXPECT_EQ(b.point->slot, 1);
}

TEST(IrTracker, FollowsTheDotNearestTheLastPositionAmongReflections) {
  IrTracker tr;
  tr.update(frame(0, {IrDot{300, 300, 4}}));
  // A bigger reflection appears; the LED moves 20 px a frame and changes slot.
  for (int i = 1; i <= 20; ++i) {
    const IrDot led{300 + 20 * i, 300 + 5 * i, 3};
    const IrDot reflection{900, 100, 9};
    const IrSlots slots = (i % 2) ? IrSlots{reflection, led} : IrSlots{led, std::nullopt, reflection};
    const IrTrackerUpdate u = tr.update(frame(i * kStep, slots));
    ASSERT_TRUE(u.point) << i;
    EXPECT_EQ(u.point->x, led.x) << i;
    EXPECT_EQ(u.point->y, led.y) << i;
    EXPECT_EQ(u.event, IrTrackerEvent::none);
  }
  EXPECT_EQ(tr.counters().rejected_jumps, 0u);
}

TEST(IrTracker, IgnoresTheSpuriousZeroDot) {
  IrTracker tr;
  const IrTrackerUpdate a = tr.update(frame(0, {IrDot{0, 0, 15}, IrDot{400, 300, 2}}));
  ASSERT_TRUE(a.point);
  EXPECT_EQ(a.point->slot, 1);
  // While tracking near the corner, (0,0) is still never taken.
  IrTracker corner;
  corner.update(frame(0, {IrDot{3, 2, 2}}));
  const IrTrackerUpdate b = corner.update(frame(kStep, {IrDot{0, 0, 2}}));
  EXPECT_FALSE(b.point);
  EXPECT_EQ(corner.counters().ignored_zero_dots, 1u);
  // A frame with only (0,0) is a frame without a dot.
  IrTracker none;
  EXPECT_FALSE(none.update(frame(0, {IrDot{0, 0, 1}})).point);
  EXPECT_FALSE(none.tracking());
}

TEST(IrTracker, RejectsAnImplausibleJumpThenFollowsItIfItPersists) {
  IrTrackerConfig cfg;
  cfg.max_speed_px_per_s = 10000;  // 100 px per 10 ms frame
  cfg.jump_slack_px = 8;
  cfg.reacquire_after_frames = 3;
  cfg.lost_after_ms = 150;
  IrTracker tr(cfg);
  tr.update(frame(0, {IrDot{200, 200, 3}}));
  // The LED vanishes and a glint 500 px away shows for two frames: rejected.
  EXPECT_FALSE(tr.update(frame(1 * kStep, {IrDot{700, 200, 3}})).point);
  EXPECT_FALSE(tr.update(frame(2 * kStep, {IrDot{702, 201, 3}})).point);
  EXPECT_EQ(tr.counters().rejected_jumps, 2u);
  // The LED is back: followed, and the glint forgotten.
  IrTrackerUpdate u = tr.update(frame(3 * kStep, {IrDot{702, 201, 3}, IrDot{210, 205, 3}}));
  ASSERT_TRUE(u.point);
  EXPECT_EQ(u.point->x, 210);
  // Now the far dot persists on its own for three consecutive frames: followed.
  EXPECT_FALSE(tr.update(frame(4 * kStep, {IrDot{800, 500, 3}})).point);
  EXPECT_FALSE(tr.update(frame(5 * kStep, {IrDot{805, 505, 3}})).point);
  u = tr.update(frame(6 * kStep, {IrDot{810, 510, 3}}));
  ASSERT_TRUE(u.point);
  EXPECT_EQ(u.event, IrTrackerEvent::jumped);
  EXPECT_EQ(u.point->x, 810);
  EXPECT_EQ(tr.counters().jumps_followed, 1u);
  // And it is tracked from there.
  u = tr.update(frame(7 * kStep, {IrDot{820, 515, 3}, IrDot{210, 205, 3}}));
  ASSERT_TRUE(u.point);
  EXPECT_EQ(u.point->x, 820);
}

TEST(IrTracker, AJumpThatHopsAroundIsNotFollowed) {
  IrTracker tr;  // 3 frames to follow a jump
  tr.update(frame(0, {IrDot{200, 200, 3}}));
  // Far dots that are not consistent with each other (flicker between two glints), both
  // farther than the LED could have gone (the bound grows with the time since the LED).
  for (int i = 1; i <= 5; ++i) {
    const IrDot glint = (i % 2) ? IrDot{1000, 50, 3} : IrDot{1000, 750, 3};
    EXPECT_FALSE(tr.update(frame(i * kStep, {glint})).point) << i;
  }
  EXPECT_EQ(tr.counters().jumps_followed, 0u);
}

TEST(IrTracker, LostAfterSilenceThenRegained) {
  IrTrackerConfig cfg;
  cfg.lost_after_ms = 150;
  IrTracker tr(cfg);
  EXPECT_EQ(tr.update(frame(0, {IrDot{500, 400, 3}})).event, IrTrackerEvent::regained);
  EXPECT_TRUE(tr.tracking());
  // Empty frames keep arriving: lost exactly once, at 150 ms.
  int lost_events = 0;
  Nanos lost_at = -1;
  for (int i = 1; i <= 30; ++i) {
    const IrTrackerUpdate u = tr.update(frame(i * kStep, {}));
    EXPECT_FALSE(u.point);
    if (u.event == IrTrackerEvent::lost) {
      ++lost_events;
      lost_at = i * kStep;
    }
  }
  EXPECT_EQ(lost_events, 1);
  EXPECT_EQ(lost_at, 15 * kStep);
  EXPECT_FALSE(tr.tracking());
  ASSERT_TRUE(tr.last_point());  // kept for display
  // The LED comes back anywhere (a far jump is fine after a loss): regained.
  const IrTrackerUpdate u = tr.update(frame(31 * kStep, {IrDot{50, 60, 1}}));
  ASSERT_TRUE(u.point);
  EXPECT_EQ(u.event, IrTrackerEvent::regained);
  EXPECT_EQ(tr.counters().lost, 1u);
  EXPECT_EQ(tr.counters().regained, 2u);
}

TEST(IrTracker, SilentRemoteIsLostByPoll) {
  IrTracker tr;  // lost after 150 ms
  tr.update(frame(0, {IrDot{500, 400, 3}}));
  EXPECT_EQ(tr.poll(100'000'000), IrTrackerEvent::none);
  EXPECT_EQ(tr.poll(150'000'000), IrTrackerEvent::lost);
  EXPECT_EQ(tr.poll(900'000'000), IrTrackerEvent::none);  // once
}

TEST(IrTracker, SurvivesEmptyAndGarbageSlots) {
  IrTracker tr;
  EXPECT_FALSE(tr.update(frame(0, {})).point);
  // Off-sensor coordinates (an empty slot read as all ones, y = 1023), negative values,
  // absurd sizes: ignored or sanitised, never a crash.
  const IrTrackerUpdate u = tr.update(frame(kStep, {IrDot{1023, 1023, 15}, IrDot{-5, 10, 2}, IrDot{INT_MAX, INT_MIN, INT_MAX},
                                                     IrDot{40, 50, 99}}));
  ASSERT_TRUE(u.point);
  EXPECT_EQ(u.point->slot, 3);
  EXPECT_EQ(u.point->size, -1);  // 99 is not a size the camera reports
  EXPECT_EQ(tr.counters().ignored_off_sensor, 3u);
  // Time going backwards or standing still: ignored and counted.
  EXPECT_FALSE(tr.update(frame(kStep, {IrDot{41, 50, 2}})).point);
  EXPECT_FALSE(tr.update(frame(0, {IrDot{41, 50, 2}})).point);
  EXPECT_EQ(tr.counters().ignored_not_after_previous, 2u);
  // Random garbage for a while, at 30 days of uptime.
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> any(-2000, 2000), coin(0, 1);
  const Nanos month = Nanos{30} * 24 * 3600 * 1'000'000'000;
  for (int i = 0; i < 5000; ++i) {
    IrSlots s;
    for (auto& slot : s)
      if (coin(rng)) slot = IrDot{any(rng), any(rng), any(rng)};
    const IrTrackerUpdate g = tr.update(frame(month + i * kStep, s));
    if (g.point) {
      EXPECT_GE(g.point->x, 0);
      EXPECT_LE(g.point->x, 1023);
      EXPECT_GE(g.point->y, 0);
      EXPECT_LE(g.point->y, 767);
    }
  }
}

TEST(IrTracker, BadConfigIsRefused) {
  EXPECT_TRUE(validate(IrTrackerConfig{}));
  IrTrackerConfig c;
  c.reacquire_after_frames = 0;
  EXPECT_FALSE(validate(c));
  EXPECT_THROW(IrTracker{c}, std::invalid_argument);
  c = {};
  c.max_speed_px_per_s = -1;
  EXPECT_FALSE(validate(c));
}

}  // namespace
}  // namespace mallet
