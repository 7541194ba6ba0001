// The mouse read at its source into the strike route: a 1000 Hz downswing as the kernel
// would deliver it (input_event frames, each stamped), decoded and handed to MousePointer
// as the evdev reading thread does. The strike's time comes from the kernel's stamps, not
// from any frame: it lies within the one millisecond between the two reports around the
// contact.
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>
#include <linux/input.h>

#include "audio/audio_setup.hpp"
#include "app/strike/mouse_pointer.hpp"
#include "input/evdev/evdev_decoder.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

constexpr Nanos kMs = 1'000'000;

input_event event(Nanos t, std::uint16_t type, std::uint16_t code, std::int32_t value) {
  input_event e{};
  e.input_event_sec = static_cast<decltype(e.input_event_sec)>(t / kNanosPerSecond);
  e.input_event_usec = static_cast<decltype(e.input_event_usec)>((t % kNanosPerSecond) / 1000);
  e.type = type;
  e.code = code;
  e.value = value;
  return e;
}

TEST(MousePointer, AThousandHertzMouseStrikesWithinAMillisecondOfItsKernelStamps) {
  const Scene& scene = test::percussion();
  const AppConfig config;
  audio::AudioRig rig = audio::make_audio_rig(scene, config, 48000);
  MousePointer mouse(scene, config, *rig.engine, nullptr);
  std::vector<Strike> struck;
  mouse.on_strike = [&](const Strike& s) { struck.push_back(s); };
  mouse.set_playing(true);

  // The screen: 1280×720 px, the pointer over bar 2's middle, 80 px above its contact plane.
  constexpr int kW = 1280, kH = 720;
  input::evdev::EvdevDecoder decoder;
  ASSERT_TRUE(decoder.set_screen(kW, kH));
  const Target& bar = scene.targets[2];
  const double plane_m = bar.top_y + scene.mallet_radius_m;
  const Vec2 contact_screen = scene.screen_to_world.unmap({0.5 * (bar.x_min + bar.x_max), plane_m});
  const double plane_px = contact_screen.y * kH;
  decoder.warp(contact_screen.x, (plane_px - 80.5) / kH);  // half a pixel off: no sample lands on the plane

  // 3 px per report at 1000 Hz, downwards; the reports stamped from t0 on.
  const Nanos t0 = 5000 * kNanosPerSecond + 123'456'000;
  std::vector<PointerSample> samples;
  for (int k = 1; k <= 60; ++k) {
    const Nanos t = t0 + k * kMs;
    for (const input_event& e : {event(t, EV_REL, REL_Y, 3), event(t, EV_SYN, SYN_REPORT, 0)})
      if (const std::optional<PointerSample> s = decoder.feed(e)) samples.push_back(*s);
  }
  ASSERT_EQ(samples.size(), 60u);
  for (std::size_t k = 0; k < samples.size(); ++k) ASSERT_EQ(samples[k].t_ns, t0 + static_cast<Nanos>(k + 1) * kMs);

  // The reading thread hands them over in batches, as they are read.
  for (std::size_t k = 0; k < samples.size(); k += 4)
    mouse.on_samples(std::span<const PointerSample>(samples).subspan(k, std::min<std::size_t>(4, samples.size() - k)));
  EXPECT_EQ(mouse.strikes(), 1u);
  EXPECT_EQ(mouse.take().size(), samples.size());  // the main thread still sees every sample

  // The first report at or below the plane, by its kernel stamp.
  std::optional<Nanos> crossing_report;
  for (const PointerSample& s : samples)
    if (!crossing_report && s.y * kH >= plane_px) crossing_report = s.t_ns;
  ASSERT_TRUE(crossing_report);
  ASSERT_EQ(struck.size(), 1u);
  const Impact& i = struck[0].impact;
  EXPECT_EQ(i.target, 2);
  // The contact lies within the millisecond before the report that crossed the plane: the
  // swept solver interpolates between the two kernel stamps around it. No frame is involved.
  EXPECT_LE(i.t_ns, *crossing_report);
  EXPECT_GT(i.t_ns, *crossing_report - kMs);
  // 3 px per ms, in metres per second through the scene's mapping.
  const double px_m = std::fabs(scene.screen_to_world.map(0, 0).y - scene.screen_to_world.map(0, 1.0 / kH).y);
  EXPECT_NEAR(i.speed_m_per_s, 3 * px_m / 1e-3, 1e-6);
  // ... and it went to the audio engine from the reading thread's ring.
  std::vector<float> block(2 * 64);
  rig.engine->process(block.data(), 64);
  EXPECT_EQ(rig.engine->counters().impacts, 1u);
  const StrikeLoop::View v = mouse.view();
  EXPECT_NEAR(v.shown.y, plane_m, 1e-9);  // the head is held on the bar
  EXPECT_NE(v.vibration.offset_m(*crossing_report + 20 * kMs), 0.0);
}

}  // namespace
}  // namespace mallet::app
