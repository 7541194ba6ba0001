// The camera's frames → LedSamples as the strike route takes them: the kept and generated
// streams through CameraTracker (decode + finder + the tracking events), and the stamps
// moved to mid-exposure.
#include <gtest/gtest.h>

#include <cmath>

#include "input/camera/camera_tracker.hpp"
#include "input/camera/frame_stamp.hpp"
#include "input/camera/frame_stream.hpp"
#include "test_paths.hpp"

namespace mallet::input::camera {
namespace {

using test::StreamFrame;
using test::StreamSpec;

std::vector<StreamFrame> kept(const char* name) {
  return test::read_frame_stream(mallet::test::source_dir() / "tests" / "input" / "camera" / name);
}

StreamSpec moving(int frames) {
  StreamSpec spec;
  spec.scene.width = 160;
  spec.scene.height = 120;
  spec.frames = frames;
  spec.rate_hz = 240;
  spec.led = {40, 60, 1.5, 180, 240, 0};  // 1 px a frame to the right
  return spec;
}

TEST(FrameStamp, TheKernelsStampIsMovedToTheExposuresMiddle) {
  const Nanos stamp = 1'000'000'000;
  EXPECT_EQ(mid_exposure_ns(stamp, StampSource::start_of_exposure, 500'000), stamp + 250'000);
  EXPECT_EQ(mid_exposure_ns(stamp, StampSource::end_of_exposure, 500'000), stamp - 250'000);
  EXPECT_EQ(mid_exposure_ns(stamp, StampSource::read_time, 500'000), stamp - 250'000);
  EXPECT_EQ(mid_exposure_ns(stamp, StampSource::end_of_exposure, -5), stamp);  // unknown exposure: as stamped
}

TEST(CameraTracker, EachFrameIsASampleAtItsOwnTimeNearTheTruth) {
  CameraTracker tracker;
  const std::vector<StreamFrame> frames = test::make_frame_stream(moving(20));
  int points = 0;
  for (const StreamFrame& f : frames) {
    const std::optional<wiimote::LedSample> s = tracker.on_frame(f.frame());
    ASSERT_TRUE(s);
    EXPECT_EQ(s->t_ns, f.t_ns);
    ASSERT_TRUE(s->has_point);
    ASSERT_TRUE(f.led);
    EXPECT_NEAR(s->point.x, f.led->x, 0.2);
    EXPECT_NEAR(s->point.y, f.led->y, 0.2);
    EXPECT_EQ(s->point.t_ns, f.t_ns);
    EXPECT_EQ(s->event, points == 0 ? IrTrackerEvent::regained : IrTrackerEvent::none);
    ++points;
  }
  EXPECT_EQ(tracker.counters().frames, 20u);
  EXPECT_EQ(tracker.counters().led_frames, 20u);
  EXPECT_EQ(tracker.counters().regained, 1u);
  EXPECT_TRUE(tracker.tracking());
}

TEST(CameraTracker, AHiddenLedIsLostAfterTheTimeOutAndRegained) {
  StreamSpec spec = moving(120);
  for (std::uint32_t q = 40; q < 90; ++q) spec.hidden.push_back(q);  // 50 frames ≈ 208 ms at 240 Hz
  CameraTracker tracker({}, 150.0);
  std::vector<std::pair<Nanos, IrTrackerEvent>> events;
  Nanos last_seen = 0;
  for (const StreamFrame& f : test::make_frame_stream(spec)) {
    const std::optional<wiimote::LedSample> s = tracker.on_frame(f.frame());
    ASSERT_TRUE(s);
    EXPECT_EQ(s->has_point, f.led.has_value()) << "frame " << f.sequence;
    if (s->event == IrTrackerEvent::lost) {
      EXPECT_GE(s->t_ns - last_seen, 150'000'000);
    }
    if (s->has_point) last_seen = s->t_ns;
    if (s->event != IrTrackerEvent::none) events.emplace_back(s->t_ns, s->event);
  }
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].second, IrTrackerEvent::regained);
  EXPECT_EQ(events[1].second, IrTrackerEvent::lost);
  EXPECT_EQ(events[2].second, IrTrackerEvent::regained);
  EXPECT_EQ(tracker.counters().lost, 1u);
}

TEST(CameraTracker, FramesTheDriverDroppedAreCountedFromTheSequence) {
  const std::vector<StreamFrame> frames = kept("dropped_frames.stream");
  ASSERT_FALSE(frames.empty());
  std::uint64_t gaps = 0;
  for (std::size_t i = 1; i < frames.size(); ++i) gaps += frames[i].sequence - frames[i - 1].sequence - 1;
  ASSERT_GT(gaps, 0u) << "the kept stream has no dropped frames";
  CameraTracker tracker;
  for (const StreamFrame& f : frames) tracker.on_frame(f.frame());
  EXPECT_EQ(tracker.counters().dropped, gaps);
  EXPECT_EQ(tracker.counters().frames, frames.size());
}

TEST(CameraTracker, AFrameNotAfterThePreviousIsIgnored) {
  const std::vector<StreamFrame> frames = test::make_frame_stream(moving(3));
  CameraTracker tracker;
  ASSERT_TRUE(tracker.on_frame(frames[1].frame()));
  EXPECT_FALSE(tracker.on_frame(frames[0].frame()));
  EXPECT_FALSE(tracker.on_frame(frames[1].frame()));
  EXPECT_TRUE(tracker.on_frame(frames[2].frame()));
  EXPECT_EQ(tracker.counters().out_of_order, 2u);
}

TEST(CameraTracker, AnUnreadableFrameIsCountedAndSaidNotGuessed) {
  std::vector<StreamFrame> frames = test::make_frame_stream(moving(3));
  frames[1].bytes.resize(100);  // a short buffer
  CameraTracker tracker;
  EXPECT_TRUE(tracker.on_frame(frames[0].frame()));
  EXPECT_FALSE(tracker.on_frame(frames[1].frame()));
  EXPECT_EQ(tracker.counters().bad_frames, 1u);
  EXPECT_NE(tracker.bad_frame().find("100"), std::string::npos) << tracker.bad_frame();
  const std::optional<wiimote::LedSample> next = tracker.on_frame(frames[2].frame());
  ASSERT_TRUE(next && next->has_point);
  EXPECT_EQ(next->event, IrTrackerEvent::none);  // still tracking across the bad frame
}

TEST(CameraTracker, OnlyUnreadableFramesLoseTheLedAfterTheTimeOut) {
  std::vector<StreamFrame> frames = test::make_frame_stream(moving(60));
  for (std::size_t i = 1; i < frames.size(); ++i) frames[i].bytes.resize(10);  // a camera sending garbage
  CameraTracker tracker({}, 150.0);
  ASSERT_TRUE(tracker.on_frame(frames[0].frame()));
  int lost = 0;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const std::optional<wiimote::LedSample> s = tracker.on_frame(frames[i].frame());
    if (s) {
      EXPECT_EQ(s->event, IrTrackerEvent::lost);
      EXPECT_GE(s->t_ns - frames[0].t_ns, 150'000'000);
      ++lost;
    }
  }
  EXPECT_EQ(lost, 1);
  EXPECT_EQ(tracker.counters().bad_frames, frames.size() - 1);
}

TEST(CameraTracker, FramesThatStopComingAreLostOnceByPoll) {
  const std::vector<StreamFrame> frames = test::make_frame_stream(moving(2));
  CameraTracker tracker({}, 150.0);
  tracker.on_frame(frames[0].frame());
  tracker.on_frame(frames[1].frame());
  EXPECT_FALSE(tracker.poll(frames[1].t_ns + 100'000'000));
  const std::optional<wiimote::LedSample> lost = tracker.poll(frames[1].t_ns + 200'000'000);
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->event, IrTrackerEvent::lost);
  EXPECT_EQ(lost->t_ns, frames[1].t_ns + 200'000'000);
  EXPECT_FALSE(tracker.poll(frames[1].t_ns + 300'000'000));
  ASSERT_TRUE(tracker.last_point());  // kept for display
}

TEST(CameraTracker, TheKeptMovingStreamIsTrackedInEveryFormat) {
  for (PixelFormat format : {PixelFormat::grey, PixelFormat::yuyv, PixelFormat::mjpeg}) {
    StreamSpec spec = moving(24);
    spec.format = format;
    CameraTracker tracker;
    double worst = 0;
    for (const StreamFrame& f : test::make_frame_stream(spec)) {
      const std::optional<wiimote::LedSample> s = tracker.on_frame(f.frame());
      ASSERT_TRUE(s && s->has_point) << name_in(kPixelFormatNames, format);
      worst = std::max(worst, std::hypot(s->point.x - f.led->x, s->point.y - f.led->y));
    }
    EXPECT_LT(worst, format == PixelFormat::mjpeg ? 0.5 : 0.2) << name_in(kPixelFormatNames, format);
  }
}

}  // namespace
}  // namespace mallet::input::camera
