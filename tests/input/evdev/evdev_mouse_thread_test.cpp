// The evdev reader's thread against a scripted libevdev (fake_libevdev.hpp) on /dev/null:
// samples reach the sink stamped with the kernel's times, SYN_DROPPED goes through
// libevdev's resync, a device that goes away is reported and opened again, stop() ends the
// thread, and open() checks what the node is. Waits are for conditions (bounded), never
// measurements of time.
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "input_event_maker.hpp"
#include "fake_libevdev.hpp"
#include "input/evdev/evdev_mouse.hpp"

namespace mallet::input::evdev {
namespace {

namespace fs = std::filesystem;

constexpr const char* kNode = "/dev/null";  // a character device that open() and poll() accept

using test::ev;

void push_move(std::int64_t t_us, int dx, int dy) {
  if (dx) fake_libevdev::push(ev(t_us, EV_REL, REL_X, dx));
  if (dy) fake_libevdev::push(ev(t_us, EV_REL, REL_Y, dy));
  fake_libevdev::push(ev(t_us, EV_SYN, SYN_REPORT, 0));
}

//! Waits (bounded) until `done` holds; false if it never did.
bool eventually(const std::function<bool()>& done) {
  for (int i = 0; i < 10'000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done();
}

//! Collects what the sink gets, from the reading thread.
struct Collector {
  std::mutex mutex;
  std::vector<PointerSample> samples;
  PointerSink sink() {
    return [this](std::span<const PointerSample> batch) {
      std::lock_guard lock(mutex);
      samples.insert(samples.end(), batch.begin(), batch.end());
    };
  }
  std::size_t size() {
    std::lock_guard lock(mutex);
    return samples.size();
  }
  std::vector<PointerSample> copy() {
    std::lock_guard lock(mutex);
    return samples;
  }
};

bool available() { return fs::is_character_file(kNode); }

class EvdevMouseThread : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!available()) GTEST_SKIP() << "no " << kNode;
    fake_libevdev::reset();
  }
};

TEST_F(EvdevMouseThread, SamplesReachTheSinkStampedWithTheKernelsTimes) {
  EvdevMouseConfig config;
  config.screen_width_px = 1000;
  config.screen_height_px = 1000;
  EvdevOpenResult r = EvdevMouse::open(kNode, config);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ(fake_libevdev::clock_id(), CLOCK_MONOTONIC);
  EXPECT_EQ((*r)->describe(), "mouse via evdev /dev/null (Fake Mouse)");
  EXPECT_TRUE((*r)->status().connected);

  push_move(93'784'000'500, 10, 0);
  push_move(93'784'001'503, 0, -20);
  push_move(93'784'002'499, 5, 5);
  Collector got;
  (*r)->start(got.sink());
  ASSERT_TRUE(eventually([&] { return got.size() == 3; }));
  (*r)->stop();
  const std::vector<PointerSample> s = got.copy();
  EXPECT_EQ(s[0].t_ns, 93'784'000'500'000);
  EXPECT_EQ(s[1].t_ns, 93'784'001'503'000);
  EXPECT_EQ(s[2].t_ns, 93'784'002'499'000);
  EXPECT_DOUBLE_EQ(s[2].x, 0.515);
  EXPECT_DOUBLE_EQ(s[2].y, 0.485);
  const EvdevMouseStatus status = (*r)->status();
  EXPECT_EQ(status.counters.samples, 3u);
  EXPECT_EQ(status.counters.reports, 3u);
  EXPECT_FALSE(status.clock_mapped);

  // Stopped: nothing more reaches the sink; a second stop is harmless; start again works.
  push_move(93'784'003'500, 1, 0);
  (*r)->stop();
  EXPECT_EQ(got.size(), 3u);
  (*r)->start(got.sink());
  ASSERT_TRUE(eventually([&] { return got.size() == 4; }));
  (*r)->stop();
}

TEST_F(EvdevMouseThread, SynDroppedIsCountedAndTheReadingGoesOn) {
  EvdevOpenResult r = EvdevMouse::open(kNode);
  ASSERT_TRUE(r) << r.error();
  push_move(1'000, 10, 0);
  fake_libevdev::push(ev(2'000, EV_REL, REL_X, 7));  // partial frame, then the drop
  fake_libevdev::push_dropped(ev(2'000, EV_SYN, SYN_DROPPED, 0));
  push_move(3'000, 1, 0);  // libevdev drained the stale events: this frame is new
  Collector got;
  (*r)->start(got.sink());
  ASSERT_TRUE(eventually([&] { return got.size() == 2; }));
  (*r)->stop();
  const std::vector<PointerSample> s = got.copy();
  EXPECT_EQ(s[1].t_ns, 3'000'000);
  EXPECT_DOUBLE_EQ(s[1].x, (960.0 + 11.0) / 1920.0);
  const EvdevMouseStatus status = (*r)->status();
  EXPECT_EQ(status.counters.dropped_syncs, 1u);
  EXPECT_EQ(status.counters.discarded_events, 1u);
}

TEST_F(EvdevMouseThread, ADeviceThatGoesAwayIsReportedAndOpenedAgain) {
  EvdevMouseConfig config;
  config.reopen_interval_ns = 10'000'000;
  EvdevOpenResult r = EvdevMouse::open(kNode, config);
  ASSERT_TRUE(r) << r.error();
  push_move(1'000, 100, 0);
  fake_libevdev::set_present(false);
  fake_libevdev::push_error(ENODEV);
  Collector got;
  (*r)->start(got.sink());
  ASSERT_TRUE(eventually([&] { return got.size() == 1 && !(*r)->status().connected; }));
  ASSERT_TRUE(eventually([&] { return (*r)->status().problem.find("last attempt") != std::string::npos; }));
  const std::string problem = (*r)->status().problem;
  EXPECT_EQ(problem.rfind("/dev/null: the device went away (No such device) (last attempt: /dev/null: not an input "
                          "event device (No such device)); trying to open it again every 0.01 s",
                          0),
            0u)
      << problem;

  fake_libevdev::set_present(true);  // plugged back in
  ASSERT_TRUE(eventually([&] { return (*r)->status().connected; }));
  push_move(5'000, 10, 0);
  ASSERT_TRUE(eventually([&] { return got.size() == 2; }));
  (*r)->stop();
  const EvdevMouseStatus status = (*r)->status();
  EXPECT_EQ(status.reconnects, 1u);
  EXPECT_EQ(status.problem, "");
  EXPECT_DOUBLE_EQ(got.copy()[1].x, (960.0 + 110.0) / 1920.0);  // the position survives the reconnection
  r->reset();
  EXPECT_EQ(fake_libevdev::created(), fake_libevdev::freed());
}

TEST_F(EvdevMouseThread, WarpAppliesBeforeTheNextSample) {
  EvdevOpenResult r = EvdevMouse::open(kNode);
  ASSERT_TRUE(r) << r.error();
  Collector got;
  (*r)->warp(0.1, 0.2);
  (*r)->set_screen(100, 100);
  (*r)->start(got.sink());
  push_move(1'000, 1, 1);
  ASSERT_TRUE(eventually([&] { return got.size() == 1; }));
  (*r)->stop();
  EXPECT_DOUBLE_EQ(got.copy()[0].x, 0.11);
  EXPECT_DOUBLE_EQ(got.copy()[0].y, 0.21);
}

TEST_F(EvdevMouseThread, AnOldKernelsRealtimeStampsAreMappedWithAnOffset) {
  fake_libevdev::reset({.set_clock_result = -EINVAL});
  EvdevOpenResult r = EvdevMouse::open(kNode);
  ASSERT_TRUE(r) << r.error();
  EXPECT_TRUE((*r)->status().clock_mapped);
  timespec wall{};
  ::clock_gettime(CLOCK_REALTIME, &wall);  // the kernel stamps on the wall clock now
  push_move(static_cast<std::int64_t>(wall.tv_sec) * 1'000'000 + wall.tv_nsec / 1'000, 1, 0);
  Collector got;
  (*r)->start(got.sink());
  ASSERT_TRUE(eventually([&] { return got.size() == 1; }));
  (*r)->stop();
  // On the program's monotonic clock (not decades of wall-clock time): a sanity bound, not a
  // measurement.
  const Nanos t = got.copy()[0].t_ns;
  EXPECT_LT(std::llabs(t - monotonic_now()), 60 * kNanosPerSecond) << t;
}

TEST_F(EvdevMouseThread, AnAbsolutePointerMapsItsRange) {
  fake_libevdev::reset({.name = "Fake Tablet", .relative = false, .left_button = false, .absolute = true});
  EvdevOpenResult r = EvdevMouse::open(kNode);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ((*r)->describe(), "pointer via evdev /dev/null (Fake Tablet, absolute)");
  fake_libevdev::push(ev(1'000, EV_ABS, ABS_X, 500));
  fake_libevdev::push(ev(1'000, EV_SYN, SYN_REPORT, 0));
  Collector got;
  (*r)->start(got.sink());
  ASSERT_TRUE(eventually([&] { return got.size() == 1; }));
  (*r)->stop();
  EXPECT_DOUBLE_EQ(got.copy()[0].x, 0.5);
  EXPECT_DOUBLE_EQ(got.copy()[0].y, 0.75);  // where the device said it was at open
}

TEST_F(EvdevMouseThread, ANodeThatIsNoPointerIsRefused) {
  fake_libevdev::reset({.name = "Fake Keyboard", .relative = false, .left_button = false});
  const EvdevOpenResult r = EvdevMouse::open(kNode);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), "/dev/null (Fake Keyboard): not a pointer (it has neither REL_X + REL_Y nor ABS_X + ABS_Y)");
  EXPECT_EQ(fake_libevdev::created(), fake_libevdev::freed());
}

TEST_F(EvdevMouseThread, FindMiceListsMiceInEventNumberOrderAndAutoOpensTheFirst) {
  const fs::path dir = fs::path(::testing::TempDir()) / "mallet_evdev_find_mice";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"event10", "event2", "mouse0"}) fs::create_symlink(kNode, dir / name);
  const std::vector<EvdevDeviceInfo> mice = find_mice(dir);
  ASSERT_EQ(mice.size(), 2u);
  EXPECT_EQ(mice[0].path, (dir / "event2").string());
  EXPECT_EQ(mice[1].path, (dir / "event10").string());
  EXPECT_EQ(mice[0].name, "Fake Mouse");

  EvdevMouseConfig config;
  config.search_dir = dir;
  EvdevOpenResult r = EvdevMouse::open(kAutoDevice, config);
  ASSERT_TRUE(r) << r.error();
  EXPECT_EQ((*r)->describe(), "mouse via evdev " + (dir / "event2").string() + " (Fake Mouse)");
  r->reset();

  fake_libevdev::reset({.left_button = false});  // REL_X + REL_Y without a button: not a mouse
  EXPECT_TRUE(find_mice(dir).empty());
  EXPECT_EQ(fake_libevdev::created(), fake_libevdev::freed());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mallet::input::evdev
