// The actuator channel: Eq. 1 from each impact's own sample, block size irrelevant,
// overlapping strikes add, the output limiter keeps the sum under its ceiling.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "audio/actuator_track.hpp"
#include "core/config/scene_config.hpp"
#include "test_paths.hpp"

namespace mallet::audio {
namespace {

Impact strike(const Scene& scene, int target, Nanos t, double v) {
  Impact i;
  i.t_ns = t;
  i.target = target;
  i.material = scene.targets[target].material;
  i.note = scene.targets[target].note;
  i.speed_m_per_s = v;
  return i;
}

std::vector<float> render(ActuatorTrack& track, std::int64_t frames, std::int64_t block) {
  std::vector<float> out(static_cast<std::size_t>(frames));
  for (std::int64_t first = 0; first < frames; first += block)
    track.render(first, std::span<float>(out).subspan(static_cast<std::size_t>(first),
                                                      static_cast<std::size_t>(std::min(block, frames - first))));
  return out;
}

TEST(ActuatorTrack, ImpactBetweenBlocksStartsOnItsOwnSampleWithExactPhase) {
  const Scene scene = config::load_scene(test::percussion_scene());
  const int fs = 48000;
  const Nanos t = 64 * 20'833 + 10'000;  // inside block 1 of 64-frame blocks, between samples
  const std::vector<Impact> impacts{strike(scene, 9, t, 1.0)};  // metal: 2.0 · 90 · 300
  ActuatorConfig config;
  config.gain = 0.2;
  ActuatorTrack track(scene, impacts, config, fs);
  const auto out = render(track, 4800, 64);
  const std::int64_t first = (t * fs + 999'999'999) / 1'000'000'000;  // ceil
  for (std::int64_t n = 0; n < first; ++n) ASSERT_EQ(out[n], 0.0f) << n;
  EXPECT_NE(out[first], 0.0f);
  for (std::int64_t n = first; n < 4800; ++n) {
    const double since = static_cast<double>(n) / fs - static_cast<double>(t) * 1e-9;
    const double want = 0.2 * 2.0 * 1.0 * std::exp(-90.0 * since) * std::sin(2 * std::numbers::pi * 300.0 * since);
    ASSERT_NEAR(out[n], want, 1e-7) << n;  // float32 output of a double computation
  }
}

TEST(ActuatorTrack, BlockSizeDoesNotChangeASingleSample) {
  const Scene scene = config::load_scene(test::percussion_scene());
  std::vector<Impact> impacts;
  for (int k = 0; k < 40; ++k) impacts.push_back(strike(scene, k % 16, 1'000'000 + k * 7'777'777, 0.5 + 0.1 * k));
  ActuatorConfig config;
  ActuatorTrack a(scene, impacts, config, 48000), b(scene, impacts, config, 48000), c(scene, impacts, config, 48000);
  const auto x = render(a, 30000, 16), y = render(b, 30000, 2048), z = render(c, 30000, 30000);
  EXPECT_EQ(x, y);
  EXPECT_EQ(x, z);
}

TEST(ActuatorTrack, ThousandSimultaneousStrikesStayUnderFullScale) {
  const Scene scene = config::load_scene(test::percussion_scene());
  std::vector<Impact> impacts;
  for (int k = 0; k < 1000; ++k) impacts.push_back(strike(scene, 8 + k % 8, 5'000'000, 10.0));
  ActuatorConfig config;
  ActuatorTrack track(scene, impacts, config, 48000);
  const auto out = render(track, 9600, 256);
  for (float s : out) {
    ASSERT_TRUE(std::isfinite(s));
    ASSERT_LE(std::fabs(s), static_cast<float>(PeakLimiter::kCeiling));
  }
  EXPECT_GT(track.clipped_samples(), 0u);
}

}  // namespace
}  // namespace mallet::audio
