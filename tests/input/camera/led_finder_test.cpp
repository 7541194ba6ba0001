// led_finder in one frame: the centroid's accuracy on a Gaussian LED, and what is refused
// (too small, too large, too long, a cluttered frame, frames with nothing in them).
#include "input/camera/led_finder.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "input/camera/frame_stream.hpp"

namespace mallet::input::camera {
namespace {

using test::draw;
using test::LumaImage;

SynthScene quiet_scene(int w = 160, int h = 120) {
  SynthScene s;
  s.width = w;
  s.height = h;
  s.read_noise = 0;
  s.shot_variance_per_level = 0;
  return s;
}

LumaImage flat(int w, int h, std::uint8_t level) {
  return {w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h), level)};
}

void fill(LumaImage& im, int x0, int y0, int x1, int y1, std::uint8_t level) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) im.pixels[static_cast<std::size_t>(y * im.width + x)] = level;
}

TEST(LedFinder, ValidateNamesTheBadKey) {
  EXPECT_TRUE(validate(LedFinderConfig{}));
  auto bad = [](auto change) {
    LedFinderConfig c;
    change(c);
    const Check r = validate(c);
    return r ? std::string() : r.error();
  };
  EXPECT_EQ(bad([](LedFinderConfig& c) { c.min_contrast = 0; }).rfind("min_contrast", 0), 0u);
  EXPECT_EQ(bad([](LedFinderConfig& c) { c.threshold_fraction = 1.0; }).rfind("threshold_fraction", 0), 0u);
  EXPECT_EQ(bad([](LedFinderConfig& c) { c.max_area_px = 2; }).rfind("max_area_px", 0), 0u);
  EXPECT_EQ(bad([](LedFinderConfig& c) { c.max_elongation = NAN; }).rfind("max_elongation", 0), 0u);
  EXPECT_EQ(bad([](LedFinderConfig& c) { c.roi_radius_px = 0; }).rfind("roi_radius_px", 0), 0u);
  EXPECT_EQ(bad([](LedFinderConfig& c) { c.track_min_sum_ratio = 2; }).rfind("track_min_sum_ratio", 0), 0u);
  LedFinderConfig c;
  c.min_area_px = 0;
  EXPECT_THROW(LedFinder{c}, std::invalid_argument);
}

TEST(LedFinder, CentroidIsSubpixelWithoutNoise) {
  LedFrameSynth synth(1);
  double worst = 0;
  for (double sigma : {1.0, 1.5, 2.5, 4.0})
    for (double fx = 0; fx < 1; fx += 0.125)
      for (double fy = 0; fy < 1; fy += 0.25) {
        SynthScene s = quiet_scene();
        s.spots.push_back({70 + fx, 50 + fy, sigma, 200});
        const LumaImage im = draw(synth, s);
        LedFinder finder;
        const LedFind f = finder.find(im.view());
        ASSERT_TRUE(f.led) << "sigma " << sigma << " at +" << fx << ",+" << fy;
        worst = std::max({worst, std::abs(f.led->x - (70 + fx)), std::abs(f.led->y - (50 + fy))});
        EXPECT_GE(f.led->area_px, 3);
        EXPECT_LT(f.led->elongation, 1.5);  // a σ 1 px LED is a handful of pixels
      }
  EXPECT_LT(worst, 0.05);
}

TEST(LedFinder, SensorNoiseGivesABoundedError) {
  LedFrameSynth synth(2);
  SynthScene s;  // read noise 1.5 levels, shot 0.1 levels² a level
  s.width = 160;
  s.height = 120;
  s.spots.push_back({80.37, 60.81, 1.5, 180});
  LedFinder finder;
  double sum2 = 0, worst = 0;
  const int n = 100;
  for (int i = 0; i < n; ++i) {
    const LedFind f = finder.find(draw(synth, s).view());
    ASSERT_TRUE(f.led);
    const double e2 = std::pow(f.led->x - 80.37, 2) + std::pow(f.led->y - 60.81, 2);
    sum2 += e2;
    worst = std::max(worst, std::sqrt(e2));
  }
  EXPECT_LT(std::sqrt(sum2 / n), 0.06);
  EXPECT_LT(worst, 0.2);
}

TEST(LedFinder, FramesWithoutALightFindNothing) {
  for (const std::uint8_t level : {std::uint8_t{0}, std::uint8_t{128}, std::uint8_t{255}}) {
    LedFinder finder;
    const LedFind f = finder.find(flat(64, 48, level).view());
    EXPECT_FALSE(f.led) << int{level};
    EXPECT_TRUE(f.full_search);
    EXPECT_EQ(f.threshold, 0);
    EXPECT_EQ(f.candidates, 0);
  }
  LedFinder finder;
  EXPECT_FALSE(finder.find(flat(1, 1, 255).view()).led);
  EXPECT_FALSE(finder.find(LumaView{}).led);
  EXPECT_EQ(finder.counters().lost, 2u);
}

TEST(LedFinder, ATinyFrameWithALightIsHandled) {
  LumaImage im = flat(2, 2, 0);
  fill(im, 0, 0, 1, 1, 0);
  im.pixels[0] = 200;
  LedFinder finder;
  const LedFind f = finder.find(im.view());  // one pixel is a hot pixel, not an LED
  EXPECT_FALSE(f.led);
  EXPECT_EQ(f.rejected.too_small, 1);
}

TEST(LedFinder, AHugeBlobIsTooLarge) {
  LumaImage im = flat(640, 480, 10);
  fill(im, 100, 100, 399, 349, 250);  // a lamp, a window
  LedFinder finder;
  const LedFind f = finder.find(im.view());
  EXPECT_FALSE(f.led);
  EXPECT_EQ(f.candidates, 1);
  EXPECT_EQ(f.rejected.too_large, 1);
}

TEST(LedFinder, ALineIsElongated) {
  LumaImage im = flat(160, 120, 10);
  fill(im, 40, 60, 60, 61, 220);  // a glint along a bar's edge
  LedFinder finder;
  const LedFind f = finder.find(im.view());
  EXPECT_FALSE(f.led);
  EXPECT_EQ(f.rejected.elongated, 1);
}

TEST(LedFinder, AClutteredFrameIsRefusedWithBoundedWork) {
  LumaImage im = flat(200, 200, 10);
  for (int y = 0; y < 200; y += 2)
    for (int x = 0; x < 200; x += 2) im.pixels[static_cast<std::size_t>(y * 200 + x)] = 240;  // 10 000 glints
  LedFinderConfig c;
  c.max_runs = 1000;
  LedFinder finder(c);
  const LedFind f = finder.find(im.view());
  EXPECT_FALSE(f.led);
  EXPECT_EQ(f.rejected.cluttered, 1);
}

TEST(LedFinder, TheStrongestOfSeveralLightsIsTheLed) {
  LedFrameSynth synth(4);
  SynthScene s = quiet_scene(320, 240);
  s.spots.push_back({40.2, 30.6, 1.5, 90});    // reflections, dimmer
  s.spots.push_back({250.7, 200.1, 1.5, 110});
  s.spots.push_back({150.4, 120.3, 1.8, 220});  // the LED
  LedFinder finder;
  const LedFind f = finder.find(draw(synth, s).view());
  ASSERT_TRUE(f.led);
  EXPECT_NEAR(f.led->x, 150.4, 0.05);
  EXPECT_NEAR(f.led->y, 120.3, 0.05);
  // The threshold follows the brightest: the dimmer ones may or may not cross it, but if
  // they do they are candidates, never the LED.
  EXPECT_GE(f.candidates, 1);
  EXPECT_GT(f.threshold, f.background);
}

TEST(LedFinder, GreyAndYuyvFindTheSameLed) {
  LedFrameSynth synth(5);
  SynthScene s;
  s.width = 96;
  s.height = 64;
  s.spots.push_back({41.3, 33.9, 1.6, 170});
  std::vector<std::uint8_t> luma;
  synth.render(s, luma);
  const auto yuyv = encode_frame(luma, 96, 64, PixelFormat::yuyv, 200);
  ASSERT_TRUE(yuyv);
  const LumaView grey_view{96, 64, luma.data(), 96, 1};
  const LumaView yuyv_view{96, 64, yuyv->data(), 200, 2};
  LedFinder a, b;
  const LedFind fa = a.find(grey_view), fb = b.find(yuyv_view);
  ASSERT_TRUE(fa.led && fb.led);
  EXPECT_EQ(fa.led->x, fb.led->x);
  EXPECT_EQ(fa.led->y, fb.led->y);
  EXPECT_EQ(fa.led->area_px, fb.led->area_px);
}

}  // namespace
}  // namespace mallet::input::camera
