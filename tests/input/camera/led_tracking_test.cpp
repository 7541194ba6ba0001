// led_finder over a sequence of frames: motion blur, the tracking square and its fallback,
// a dimmer second light, and a lost LED. 640×480 over the kiosk's 0.82 m (1.28 mm a pixel),
// 240 frames a second, 1 ms exposure.
#include "input/camera/led_finder.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "input/camera/frame_stream.hpp"

namespace mallet::input::camera {
namespace {

using test::draw;

constexpr double kMmPerPx = 820.0 / 640.0;
constexpr double kRateHz = 240;
constexpr double px_per_s(double m_per_s) { return m_per_s * 1000.0 / kMmPerPx; }

SynthScene scene_640(bool noise) {
  SynthScene s;
  s.exposure_s = 0.001;
  if (!noise) s.read_noise = s.shot_variance_per_level = 0;
  return s;
}

SynthSpot led_at(double x, double y, double vx = 0, double vy = 0) { return {x, y, 1.8, 200, vx, vy}; }

TEST(LedTracking, MotionBlurIsFoundAndCentredOnTheExposuresMiddle) {
  LedFrameSynth synth(21);
  double elongation[2] = {0, 0};
  for (const double speed : {0.2, 4.0})
    for (const bool noise : {false, true}) {
      const double v = px_per_s(speed);  // 4 m/s: a 3.1 px streak in 1 ms
      SynthScene s = scene_640(noise);
      s.spots.push_back(led_at(300.3, 200.6, 0.6 * v, -0.8 * v));
      LedFinder finder;
      const LedFind f = finder.find(draw(synth, s).view());
      ASSERT_TRUE(f.led) << speed << " m/s";
      const double tol = noise ? 0.15 : 0.05;
      EXPECT_NEAR(f.led->x, 300.3, tol) << speed << " m/s";
      EXPECT_NEAR(f.led->y, 200.6, tol) << speed << " m/s";
      if (!noise) elongation[speed > 1] = f.led->elongation;
    }
  EXPECT_GT(elongation[1], elongation[0]);  // the streak is seen as one blob, longer
}

TEST(LedTracking, TheSquareFollowsAMovingLed) {
  LedFrameSynth synth(22);
  const double v = px_per_s(4.0);  // 13 px a frame
  LedFinder finder;
  for (int i = 0; i < 30; ++i) {
    const double t = i / kRateHz;
    SynthScene s = scene_640(true);
    s.spots.push_back(led_at(100 + 0.8 * v * t, 400 - 0.6 * v * t, 0.8 * v, -0.6 * v));
    const LedFind f = finder.find(draw(synth, s).view());
    ASSERT_TRUE(f.led) << "frame " << i;
    EXPECT_EQ(f.full_search, i == 0) << "frame " << i;
    EXPECT_NEAR(f.led->x, s.spots[0].x, 0.2) << "frame " << i;
    EXPECT_NEAR(f.led->y, s.spots[0].y, 0.2) << "frame " << i;
  }
  EXPECT_EQ(finder.counters().full_searches, 1u);
  EXPECT_EQ(finder.counters().roi_misses, 0u);
}

TEST(LedTracking, AJumpOutOfTheSquareFallsBackToAFullSearch) {
  LedFrameSynth synth(23);
  LedFinder finder;
  SynthScene s = scene_640(true);
  s.spots.push_back(led_at(120.4, 100.2));
  ASSERT_TRUE(finder.find(draw(synth, s).view()).led);
  ASSERT_FALSE(finder.find(draw(synth, s).view()).full_search);
  s.spots[0] = led_at(500.7, 380.3);  // far beyond roi_radius_px
  const LedFind f = finder.find(draw(synth, s).view());
  ASSERT_TRUE(f.led);
  EXPECT_TRUE(f.full_search);
  EXPECT_NEAR(f.led->x, 500.7, 0.2);
  EXPECT_NEAR(f.led->y, 380.3, 0.2);
  EXPECT_EQ(finder.counters().roi_misses, 1u);
  EXPECT_FALSE(finder.find(draw(synth, s).view()).full_search);  // tracking again
}

TEST(LedTracking, ADimmerReflectionIsNotChosenWhenAcquiring) {
  LedFrameSynth synth(24);
  for (const bool reflection_first : {false, true}) {
    SynthScene s = scene_640(true);
    const SynthSpot reflection{320.5, 240.5, 1.8, 90};
    if (reflection_first) s.spots.push_back(reflection);
    s.spots.push_back(led_at(200.2, 150.7));
    if (!reflection_first) s.spots.push_back(reflection);
    LedFinderConfig c;
    c.threshold_fraction = 0;  // both lights above the threshold: a real choice
    LedFinder finder(c);
    const LedFind f = finder.find(draw(synth, s).view());
    ASSERT_TRUE(f.led);
    EXPECT_EQ(f.candidates, 2);
    EXPECT_NEAR(f.led->x, 200.2, 0.2);
    EXPECT_NEAR(f.led->y, 150.7, 0.2);
  }
}

TEST(LedTracking, ADimmerReflectionIsNotFollowedWhileTracking) {
  LedFrameSynth synth(25);
  LedFinderConfig c;
  c.threshold_fraction = 0;  // the reflection crosses the threshold whenever it is searched
  LedFinder finder(c);
  const double v = px_per_s(2.0);
  const SynthSpot reflection{330.0, 252.0, 2.0, 70};
  // The LED passes 12 px from the reflection, inside the tracking square for many frames.
  for (int i = 0; i < 40; ++i) {
    const double t = i / kRateHz;
    SynthScene s = scene_640(true);
    s.spots.push_back(led_at(250 + v * t, 240, v, 0));
    s.spots.push_back(reflection);
    const LedFind f = finder.find(draw(synth, s).view());
    ASSERT_TRUE(f.led) << "frame " << i;
    EXPECT_NEAR(f.led->x, s.spots[0].x, 0.3) << "frame " << i;
    EXPECT_NEAR(f.led->y, 240, 0.3) << "frame " << i;
  }
  // Hidden (a hand over it) next to the reflection: the reflection is too dim to be it.
  SynthScene s = scene_640(true);
  s.spots.push_back(reflection);
  const LedFind hidden = finder.find(draw(synth, s).view());
  EXPECT_FALSE(hidden.led);
  EXPECT_TRUE(hidden.full_search);
  EXPECT_EQ(hidden.rejected.too_dim, 1);
}

TEST(LedTracking, ALostLedReportsNoneThenIsAcquiredAgain) {
  LedFrameSynth synth(26);
  LedFinder finder;
  SynthScene s = scene_640(true);
  s.spots.push_back(led_at(222.2, 111.1));
  ASSERT_TRUE(finder.find(draw(synth, s).view()).led);
  SynthScene blank = scene_640(true);
  for (int i = 0; i < 3; ++i) {
    const LedFind f = finder.find(draw(synth, blank).view());
    EXPECT_FALSE(f.led);
    EXPECT_TRUE(f.full_search);
    EXPECT_EQ(f.threshold, 0);  // noise alone never reaches min_contrast
  }
  EXPECT_EQ(finder.counters().lost, 3u);
  s.spots[0] = led_at(400.6, 300.4);
  const LedFind back = finder.find(draw(synth, s).view());
  ASSERT_TRUE(back.led);
  EXPECT_TRUE(back.full_search);
  EXPECT_NEAR(back.led->x, 400.6, 0.2);
  EXPECT_EQ(finder.counters().found, 2u);
}

TEST(LedTracking, ResetForgetsTheTrack) {
  LedFrameSynth synth(27);
  LedFinder finder;
  SynthScene s = scene_640(false);
  s.spots.push_back(led_at(50.5, 60.5));
  ASSERT_TRUE(finder.find(draw(synth, s).view()).led);
  finder.reset();
  EXPECT_TRUE(finder.find(draw(synth, s).view()).full_search);
}

}  // namespace
}  // namespace mallet::input::camera
