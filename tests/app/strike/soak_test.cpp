// The soak: a day of kiosk life, compressed. Every simulated hour a visitor plays the
// shipped demo tune (replayed), then nobody is there and the attract mode plays for the
// rest of the hour; a small frame is rendered every simulated minute. The audio runs at
// 4 kHz (every sample is still computed; the stimuli's bands fit: the actuator's highest
// frequency is 300 Hz) so that 24 h of it fit in CI under ASan.
//
// Asserted: no NaN or inf in any sample, no lost impact (every strike the solver found is
// posted and counted by the engine; every replayed strike is accounted for each hour), no
// voice left sounding after the last strike has decayed, and no heap growth between the
// first hour and the last beyond a small bound.
#include <cstddef>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "app/strike/headless_loop.hpp"
#include "render/render_setup.hpp"
#include "app/strike/replay.hpp"
#include "input/trajectory_csv.hpp"
#include "test_paths.hpp"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MALLET_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define MALLET_ASAN 1
#endif

#ifdef MALLET_ASAN
// From the sanitizer runtime (GCC does not ship its header, clang does).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#else
#include <malloc.h>
#endif

namespace mallet::app {
namespace {

//! Bytes of heap in use now (the sanitizer's own count under ASan: its quarantine makes
//! the process size useless there).
std::size_t heap_in_use() {
#ifdef MALLET_ASAN
  return __sanitizer_get_current_allocated_bytes();
#else
  return mallinfo2().uordblks;
#endif
}

constexpr Nanos kHour = 3600 * kNanosPerSecond;
constexpr Nanos kMinute = 60 * kNanosPerSecond;

TEST(Soak, ADayOfVisitorsAndAttractModeLosesNothingAndDoesNotGrow) {
  const Scene& scene = test::percussion();
  AppConfig config;
  config.audio.sample_rate_hz = 4000;
  const input::Trajectory demo =
      input::read_trajectory_csv(test::source_dir() / "config" / "trajectories" / "demo.csv");
  // What one visit strikes, by itself (the replay's own count is the truth to account for).
  const Replay alone(scene, config, demo, InputSpace::screen, "demo.csv");
  ASSERT_GT(alone.impacts().size(), 3u);

  HeadlessLoop loop(scene, config, 45 * kNanosPerSecond);
  std::uint64_t strikes_seen = 0;
  loop.on_strike = [&](const Strike&, bool) { ++strikes_seen; };

  render::HeadlessOptions ho;
  ho.size = {64, 36};
  ho.validation = render::Validation::off;
  ho.cache_dir = "";
  render::HeadlessRenderer renderer(scene, ho);

  std::size_t heap_after_first_hour = 0;  // after two hours, once pools have settled
  for (int hour = 0; hour < 24; ++hour) {
    const Nanos start = hour * kHour + kMinute;  // the attract mode plays before the visitor
    const std::uint64_t visitor_before = loop.counters().visitor_strikes;
    for (const PointerSample& s : demo.samples)
      loop.visitor(start + s.t_ns, scene.screen_to_world.map(s.x, s.y));
    EXPECT_EQ(loop.counters().visitor_strikes - visitor_before, alone.impacts().size()) << "hour " << hour;
    for (Nanos t = loop.now(); t < (hour + 1) * kHour; t += kMinute) {
      loop.advance(t);
      render::FrameState state;
      state.mallet_centre = loop.displayed(t);
      renderer.draw(state);
    }
    EXPECT_TRUE(loop.attract()) << "nobody played for most of hour " << hour;
    if (hour == 1) heap_after_first_hour = heap_in_use();
    if (std::getenv("MALLET_SOAK_TRACE")) std::printf("hour %d: heap %zu B\n", hour, heap_in_use());
  }
  const Nanos end = 24 * kHour;
  loop.advance(end);
  const std::size_t heap_at_end = heap_in_use();

  const HeadlessLoop::Counters& c = loop.counters();
  EXPECT_EQ(c.non_finite_samples, 0u);
  EXPECT_EQ(loop.engine().counters().dropped, 0u);  // no strike refused by a full ring
  EXPECT_EQ(c.visitor_strikes, 24 * alone.impacts().size());
  EXPECT_GT(c.ghost_strikes, 10000u) << "the attract mode played all day";
  EXPECT_EQ(strikes_seen, c.visitor_strikes + c.ghost_strikes);
  EXPECT_EQ(c.audio_frames, static_cast<std::uint64_t>(24 * 3600 * 4000));
  EXPECT_LE(c.peak, 1.0);

  // After the last strike has rung out, no voice is left.
  loop.drain_audio(end + 30 * kNanosPerSecond);
  const audio::EngineCounters e = loop.engine().counters();
  EXPECT_EQ(e.impacts, strikes_seen) << "every posted strike reached the engine";
  EXPECT_EQ(e.dropped, 0u);
  EXPECT_EQ(e.active_voices, 0);

  // A day of use must not grow the heap. Measured: flat but for one step of 1 MiB in the
  // third hour (an allocator or driver pool settling), then flat to the end. 4 MiB over
  // the ≈170 000 strikes of hours 2–24 still catches a leak of 25 bytes per strike.
  EXPECT_LT(static_cast<double>(heap_at_end), static_cast<double>(heap_after_first_hour) + 4.0 * 1024 * 1024)
      << "heap after 2 h: " << heap_after_first_hour << " B, after 24 h: " << heap_at_end << " B";
}

}  // namespace
}  // namespace mallet::app
