// The evdev decoder on recorded event streams (this machine has no mouse and no
// /dev/uinput): a 1000 Hz mouse gives 1000 samples a second, each stamped with the kernel's
// own timestamp of its frame; SYN_DROPPED discards the incomplete frames; the pointer is
// clamped to the screen, warped, scaled by a constant speed (no acceleration), and its time
// shifted by the clock offset; absolute axes map their range onto the screen.
#include "input_event_maker.hpp"
#include "input/evdev/evdev_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "input/evdev/evemu_file.hpp"
#include "input/evdev/rate_meter.hpp"

namespace mallet::input::evdev {
namespace {

std::filesystem::path recording() {
  return std::filesystem::path(MALLET_TEST_SOURCE_DIR) / "tests/input/evdev/mouse_1000hz.evemu";
}

//! The first frame's kernel time in the recording: 93784.000500 s (26 h of uptime).
constexpr Nanos kRecordingStartNs = 93'784'000'500'000;

using test::ev;
input_event rel_x(std::int64_t t_us, int v) { return ev(t_us, EV_REL, REL_X, v); }
input_event rel_y(std::int64_t t_us, int v) { return ev(t_us, EV_REL, REL_Y, v); }
input_event syn(std::int64_t t_us) { return ev(t_us, EV_SYN, SYN_REPORT, 0); }
input_event dropped(std::int64_t t_us) { return ev(t_us, EV_SYN, SYN_DROPPED, 0); }

std::vector<PointerSample> feed_all(EvdevDecoder& decoder, const std::vector<input_event>& events) {
  std::vector<PointerSample> out;
  for (const input_event& e : events) {
    if (auto s = decoder.feed(e)) out.push_back(*s);
  }
  return out;
}

TEST(EvdevDecoder, A1000HzMouseGives1000SamplesASecondStampedWithTheKernelsTimes) {
  const std::vector<input_event> events = read_evemu_events(recording());
  EvdevDecoder decoder;  // 1920 × 1080, 1 px per count, starting at the centre
  std::vector<PointerSample> samples;
  for (const input_event& e : events) {
    const auto sample = decoder.feed(e);
    if (!sample) continue;
    // Exactly the SYN_REPORT's kernel stamp, converted here without the decoder's helper.
    ASSERT_EQ(e.type, EV_SYN);
    const Nanos kernel_ns = static_cast<Nanos>(e.input_event_sec) * 1'000'000'000 +
                            static_cast<Nanos>(e.input_event_usec) * 1'000;
    ASSERT_EQ(sample->t_ns, kernel_ns) << samples.size();
    samples.push_back(*sample);
  }
  ASSERT_EQ(samples.size(), 1000u);
  EXPECT_EQ(samples.front().t_ns, kRecordingStartNs);

  // 1000 in the first second, none beyond: the button-only and wheel-only frames after it
  // are reports without motion.
  const auto in_first_second = std::count_if(samples.begin(), samples.end(), [](const PointerSample& s) {
    return s.t_ns >= kRecordingStartNs && s.t_ns < kRecordingStartNs + kNanosPerSecond;
  });
  EXPECT_EQ(in_first_second, 1000);
  RateMeter rate;
  for (const PointerSample& s : samples) rate.add(s.t_ns);
  EXPECT_EQ(rate.rate_hz(samples.back().t_ns), 1000.0);

  // The USB polling jitter (a few µs) is kept, not rounded to a frame or a millisecond.
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const Nanos dt = samples[i].t_ns - samples[i - 1].t_ns;
    EXPECT_GE(dt, 990'000) << i;
    EXPECT_LE(dt, 1'010'000) << i;
  }
  EXPECT_NE(samples[1].t_ns - samples[0].t_ns, 1'000'000);

  const EvdevDecoderCounters& c = decoder.counters();
  EXPECT_EQ(c.reports, 1002u);
  EXPECT_EQ(c.samples, 1000u);
  EXPECT_EQ(c.dropped_syncs, 0u);
  EXPECT_EQ(c.discarded_events, 0u);

  // The stroke: +750 counts right and 400 down by frame 499, then back to the centre.
  EXPECT_DOUBLE_EQ(samples[499].x, (960.0 + 750.0) / 1920.0);
  EXPECT_DOUBLE_EQ(samples[499].y, (540.0 + 400.0) / 1080.0);
  EXPECT_DOUBLE_EQ(samples.back().x, 0.5);
  EXPECT_DOUBLE_EQ(samples.back().y, 0.5);
  EXPECT_FALSE(decoder.left_button());  // pressed in frame 400, released in frame 1000
}

TEST(EvdevDecoder, TheButtonChangesAtItsFrame) {
  EvdevDecoder decoder;
  decoder.feed(ev(10, EV_KEY, BTN_LEFT, 1));
  EXPECT_FALSE(decoder.left_button());  // not before the frame is complete
  EXPECT_FALSE(decoder.feed(syn(10)));  // a button alone is no motion
  EXPECT_TRUE(decoder.left_button());
  EXPECT_EQ(decoder.counters().reports, 1u);
  EXPECT_EQ(decoder.counters().samples, 0u);
}

TEST(EvdevDecoder, SynDroppedDiscardsThePartialFrameAndEverythingUpToTheNextReport) {
  EvdevDecoder decoder;
  decoder.set_screen(1000, 1000);
  const std::vector<PointerSample> samples = feed_all(decoder, {
      rel_x(1000, 10), syn(1000),                    // kept
      rel_x(2000, 5),                                // partial: discarded by the drop
      dropped(2500),                                 //
      rel_x(3000, 7), rel_y(3000, 3), syn(3000),     // incomplete frame: discarded
      rel_x(4000, 1), syn(4000),                     // kept
  });
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].t_ns, 1'000'000);
  EXPECT_EQ(samples[1].t_ns, 4'000'000);
  EXPECT_DOUBLE_EQ(samples[1].x, (500.0 + 10 + 1) / 1000.0);  // the lost counts are lost: no jump
  EXPECT_DOUBLE_EQ(samples[1].y, 0.5);
  const EvdevDecoderCounters& c = decoder.counters();
  EXPECT_EQ(c.dropped_syncs, 1u);
  EXPECT_EQ(c.discarded_events, 4u);  // REL_X 5; REL_X 7, REL_Y 3 and their SYN_REPORT
  EXPECT_EQ(c.reports, 2u);
  EXPECT_EQ(c.samples, 2u);
}

TEST(EvdevDecoder, AfterLibevdevsResyncTheSyncedFrameIsTaken) {
  EvdevDecoder decoder;
  decoder.set_screen(1000, 1000);
  decoder.feed(rel_x(1000, 9));
  decoder.feed(dropped(1000));
  decoder.resynced();  // libevdev drained the stale events itself
  const std::vector<PointerSample> samples = feed_all(decoder, {rel_x(2000, 4), syn(2000)});
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_DOUBLE_EQ(samples[0].x, 0.504);  // the 9 before the drop are gone
  EXPECT_EQ(decoder.counters().dropped_syncs, 1u);
  EXPECT_EQ(decoder.counters().discarded_events, 1u);
}

TEST(EvdevDecoder, ThePointerIsClampedToTheScreenWithoutBankingTheOvershoot) {
  EvdevDecoder decoder;
  decoder.set_screen(100, 50);
  auto s = feed_all(decoder, {rel_x(1, -1000), rel_y(1, 1000), syn(1)});
  ASSERT_EQ(s.size(), 1u);  // a frame that moved against the edge still is a sample
  EXPECT_EQ(s[0].x, 0.0);
  EXPECT_EQ(s[0].y, 1.0);
  s = feed_all(decoder, {rel_x(2, 1), rel_y(2, -5), syn(2)});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s[0].x, 0.01);  // back off the edge at once
  EXPECT_DOUBLE_EQ(s[0].y, 45.0 / 50.0);
  s = feed_all(decoder, {rel_x(3, 5000), rel_y(3, -5000), syn(3)});
  EXPECT_EQ(s[0].x, 1.0);
  EXPECT_EQ(s[0].y, 0.0);
}

TEST(EvdevDecoder, WarpSetsThePositionWithoutASample) {
  EvdevDecoder decoder;
  decoder.set_screen(200, 100);
  decoder.warp(0.25, 0.75);
  EXPECT_EQ(decoder.counters().samples, 0u);
  EXPECT_DOUBLE_EQ(decoder.position().x, 0.25);
  EXPECT_DOUBLE_EQ(decoder.position().y, 0.75);
  const auto s = feed_all(decoder, {rel_x(1, 10), syn(1)});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s[0].x, 0.30);
  EXPECT_DOUBLE_EQ(s[0].y, 0.75);

  decoder.warp(-3, 7);  // clamped
  EXPECT_EQ(decoder.position().x, 0.0);
  EXPECT_EQ(decoder.position().y, 1.0);
  decoder.warp(std::numeric_limits<double>::quiet_NaN(), 0.5);  // a NaN would stick: ignored
  EXPECT_EQ(decoder.position().x, 0.0);
  EXPECT_EQ(decoder.position().y, 0.5);
}

TEST(EvdevDecoder, SpeedScalesCountsTheSameAtEverySpeed) {
  EvdevDecoder slow_and_many, fast_and_one;
  for (EvdevDecoder* d : {&slow_and_many, &fast_and_one}) {
    d->set_screen(1000, 1000);
    ASSERT_TRUE(d->set_speed(2.5));
  }
  // 10 frames of 1 count (a slow hand) and 1 frame of 10 counts (a fast one): no acceleration,
  // so the same distance, 10 × 2.5 px.
  for (int i = 0; i < 10; ++i) feed_all(slow_and_many, {rel_x(i, 1), syn(i)});
  feed_all(fast_and_one, {rel_x(0, 10), syn(0)});
  EXPECT_DOUBLE_EQ(slow_and_many.position().x, (500.0 + 25.0) / 1000.0);
  EXPECT_DOUBLE_EQ(fast_and_one.position().x, slow_and_many.position().x);

  EvdevDecoder d;
  EXPECT_FALSE(d.set_speed(0));
  EXPECT_FALSE(d.set_speed(-1));
  EXPECT_FALSE(d.set_speed(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(d.speed_px_per_count(), EvdevDecoder::kDefaultSpeedPxPerCount);
  EXPECT_FALSE(d.set_screen(0, 100));
  EXPECT_EQ(d.screen_width_px(), EvdevDecoder::kDefaultScreenWidthPx);
}

TEST(EvdevDecoder, SetScreenKeepsTheNormalisedPosition) {
  EvdevDecoder decoder;
  decoder.warp(0.3, 0.6);
  ASSERT_TRUE(decoder.set_screen(1000, 500));
  EXPECT_DOUBLE_EQ(decoder.position().x, 0.3);
  EXPECT_DOUBLE_EQ(decoder.position().y, 0.6);
  feed_all(decoder, {rel_x(1, 100), rel_y(1, 50), syn(1)});  // now in the new screen's pixels
  EXPECT_DOUBLE_EQ(decoder.position().x, 0.4);
  EXPECT_DOUBLE_EQ(decoder.position().y, 0.7);
}

TEST(EvdevDecoder, TheClockOffsetShiftsEveryStampExactly) {
  const std::vector<input_event> events = read_evemu_events(recording());
  EvdevDecoder plain, mapped;
  constexpr Nanos kOffset = -1'700'000'000'123'456'789;  // e.g. CLOCK_REALTIME → CLOCK_MONOTONIC
  mapped.set_clock_offset(kOffset);
  const std::vector<PointerSample> a = feed_all(plain, events);
  const std::vector<PointerSample> b = feed_all(mapped, events);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(b[i].t_ns, a[i].t_ns + kOffset) << i;
    ASSERT_EQ(b[i].x, a[i].x) << i;
  }
}

TEST(EvdevDecoder, AbsoluteAxesMapTheirRangeOntoTheScreen) {
  EvdevDecoder decoder;
  decoder.set_abs_range(ABS_X, {0, 4000});
  decoder.set_abs_range(ABS_Y, {-100, 100});
  auto s = feed_all(decoder, {ev(5, EV_ABS, ABS_X, 1000), ev(5, EV_ABS, ABS_Y, 100), syn(5)});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].t_ns, 5'000);
  EXPECT_DOUBLE_EQ(s[0].x, 0.25);
  EXPECT_DOUBLE_EQ(s[0].y, 1.0);
  s = feed_all(decoder, {ev(6, EV_ABS, ABS_Y, -50), syn(6)});  // one axis: the other stays
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s[0].x, 0.25);
  EXPECT_DOUBLE_EQ(s[0].y, 0.25);
  s = feed_all(decoder, {ev(7, EV_ABS, ABS_X, 9000), syn(7)});  // past the range: clamped
  EXPECT_EQ(s[0].x, 1.0);

  EvdevDecoder unranged;  // no range known: ABS is not a position
  EXPECT_TRUE(feed_all(unranged, {ev(1, EV_ABS, ABS_X, 10), syn(1)}).empty());
  unranged.set_abs_range(ABS_X, {5, 5});  // an empty range is no range
  EXPECT_TRUE(feed_all(unranged, {ev(2, EV_ABS, ABS_X, 10), syn(2)}).empty());
}

TEST(EvdevDecoder, OtherEventsAreNotMotion) {
  EvdevDecoder decoder;
  const auto s = feed_all(decoder, {ev(1, EV_REL, REL_WHEEL, -1), ev(1, EV_MSC, MSC_SCAN, 589825), syn(1),
                                    ev(2, EV_SYN, SYN_MT_REPORT, 0), ev(2, EV_REL, REL_HWHEEL, 1), syn(2)});
  EXPECT_TRUE(s.empty());
  EXPECT_EQ(decoder.counters().reports, 2u);
  EXPECT_DOUBLE_EQ(decoder.position().x, 0.5);
}

}  // namespace
}  // namespace mallet::input::evdev
