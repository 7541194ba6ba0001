// The camera's reading thread over a scripted grabber: samples reach the sink in order, a
// camera that goes away is reopened (forever, as the remote is), a camera that is not there
// yet is waited for, and stop() ends a waiting read.
#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <thread>

#include "input/camera/camera_device.hpp"
#include "input/camera/frame_stream.hpp"
#include "input/camera/scripted_grabber.hpp"
#include "input/wiimote/wiimote_test_support.hpp"

namespace mallet::input::camera {
namespace {

std::vector<test::StreamFrame> frames(int n) {
  test::StreamSpec spec;
  spec.scene.width = 160;
  spec.scene.height = 120;
  spec.frames = n;
  spec.led = {50, 40, 1.5, 180, 0, 240};
  return test::make_frame_stream(spec);
}

//! Everything the sink got, for the test thread.
struct Collected {
  std::mutex mutex;
  std::vector<wiimote::LedSample> samples;
  std::size_t size() {
    std::lock_guard lock(mutex);
    return samples.size();
  }
};

//! Waits (bounded) until `done`; the bound only keeps a broken device from hanging the test.
template <typename F>
bool eventually(F done) {
  for (int i = 0; i < 5000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done();
}

TEST(CameraDevice, EveryFramesSampleReachesTheSinkInOrder) {
  wiimote::test::FakeClock clock;
  auto grabber = std::make_unique<test::ScriptedGrabber>(test::ScriptedGrabber::Script{frames(30)});
  CameraDevice device(std::move(grabber), clock);
  Collected got;
  device.set_sample_sink([&](std::span<const wiimote::LedSample> s, Nanos) {
    std::lock_guard lock(got.mutex);
    got.samples.insert(got.samples.end(), s.begin(), s.end());
  });
  device.start();
  ASSERT_TRUE(eventually([&] { return got.size() >= 30; }));
  device.stop();
  const std::vector<test::StreamFrame> truth = frames(30);
  for (std::size_t i = 0; i < 30; ++i) {
    EXPECT_EQ(got.samples[i].t_ns, truth[i].t_ns);
    ASSERT_TRUE(got.samples[i].has_point);
    EXPECT_NEAR(got.samples[i].point.y, truth[i].led->y, 0.2);
  }
  EXPECT_EQ(got.samples[0].event, IrTrackerEvent::regained);
  const CameraStatus s = device.status();
  EXPECT_EQ(s.counters.frames, 30u);
  EXPECT_EQ(s.mode.name, "Scripted Camera");
  EXPECT_EQ(s.mode.stamping, "scripted");
  EXPECT_EQ(device.describe(), "camera /dev/video7 (Scripted Camera, test) 160x120 grey at 240 Hz");
}

TEST(CameraDevice, ACameraThatGoesAwayIsLostThenOpenedAgain) {
  wiimote::test::FakeClock clock;
  test::ScriptedGrabber::Script script{frames(20), 10, 0};
  auto owned = std::make_unique<test::ScriptedGrabber>(script);
  test::ScriptedGrabber* grabber = owned.get();
  CameraDevice device(std::move(owned), clock);
  Collected got;
  device.set_sample_sink([&](std::span<const wiimote::LedSample> s, Nanos) {
    std::lock_guard lock(got.mutex);
    got.samples.insert(got.samples.end(), s.begin(), s.end());
  });
  device.start();
  ASSERT_TRUE(eventually([&] { return got.size() >= 21; }));  // 20 frames and one `lost`
  device.stop();
  EXPECT_EQ(grabber->opens(), 2);
  EXPECT_EQ(device.status().reconnects, 1u);
  // The loss is counted with its reason, kept after the reopening (and stop() is no loss):
  // the kiosk tells a loss it did not see because the camera was back before it looked.
  EXPECT_EQ(device.status().losses, 1u);
  EXPECT_EQ(device.status().last_loss, "/dev/video7: No such device");
  // 10 frames, `lost` when it went away, the 10 frames after the reopen (after them a
  // camera that sends nothing more loses the LED too: not counted here).
  int lost = 0, regained = 0;
  for (std::size_t i = 0; i < 21; ++i) {
    lost += got.samples[i].event == IrTrackerEvent::lost;
    regained += got.samples[i].event == IrTrackerEvent::regained;
  }
  EXPECT_EQ(lost, 1);
  EXPECT_EQ(regained, 2);
  EXPECT_EQ(got.samples[10].event, IrTrackerEvent::lost);
}

TEST(CameraDevice, ACameraNotThereYetIsWaitedForAndSaidWhy) {
  wiimote::test::FakeClock clock;
  test::ScriptedGrabber::Script script{frames(5), SIZE_MAX, 3};
  auto owned = std::make_unique<test::ScriptedGrabber>(script);
  test::ScriptedGrabber* grabber = owned.get();
  CameraDevice device(std::move(owned), clock);
  std::atomic<int> samples{0};
  device.set_sample_sink([&](std::span<const wiimote::LedSample> s, Nanos) { samples += static_cast<int>(s.size()); });
  EXPECT_EQ(device.describe(), "camera: not opened yet");
  device.start();
  ASSERT_TRUE(eventually([&] { return grabber->opens() >= 1; }));
  ASSERT_TRUE(eventually([&] { return samples.load() >= 5; }));
  device.stop();
  EXPECT_EQ(grabber->opens(), 4);
  EXPECT_EQ(device.status().reconnects, 0u);  // the first success is a connection, not a reconnection
}

TEST(CameraDevice, StopEndsTheThreadOfACameraThatNeverOpens) {
  wiimote::test::FakeClock clock;
  test::ScriptedGrabber::Script script{{}, SIZE_MAX, 1 << 30};
  CameraDevice device(std::make_unique<test::ScriptedGrabber>(script), clock);
  device.start();
  ASSERT_TRUE(eventually([&] { return device.status().problem == "no camera among /dev/video*"; }));
  device.stop();
  EXPECT_FALSE(device.status().connected);
  EXPECT_EQ(device.status().problem, "no camera among /dev/video*");  // stopping keeps why it never opened
  EXPECT_EQ(device.describe(), "camera: no camera among /dev/video*");
}

}  // namespace
}  // namespace mallet::input::camera
