// The live remote's device logic against an in-process fake remote and a scripted clock:
// connection and IR start-up, LED samples stamped at reception, silence → reconnect with
// a capped back-off and a fresh start-up, 0x20 → 0x12 again, rumble pulses, open
// failures, device selection, the reading thread. No test sleeps or measures time.
#include "input/wiimote/wiimote_device.hpp"

#include <chrono>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "fake_remote.hpp"

namespace mallet::input::wiimote {
namespace {

using namespace test;

//! Steps until `done` (at most `max_steps`: a bug must fail, not hang).
bool step_until(WiimoteDevice& device, const std::function<bool()>& done, int max_steps = 100'000) {
  for (int i = 0; i < max_steps; ++i) {
    if (done()) return true;
    device.step();
  }
  return done();
}

bool running(const WiimoteDevice& d) { return d.state().link == LinkState::running; }

struct Rig {
  FakeClock clock;
  FakeFinder finder{clock};
  std::shared_ptr<FakeRemote> remote = finder.add("/dev/hidraw3", "00:1f:32:aa:bb:cc");
};

TEST(WiimoteDevice, ConnectsRunsTheIrStartupAndPublishesTheLedStampedAtReception) {
  Rig rig;
  WiimoteDevice device(rig.finder, rig.clock);
  EXPECT_EQ(device.state().link, LinkState::searching);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  EXPECT_EQ(rig.remote->written, connect_sequence());
  WiimoteState s = device.state();
  EXPECT_EQ(s.device.path, "/dev/hidraw3");
  EXPECT_EQ(s.connects, 1u);
  EXPECT_EQ(s.startup, IrStartupStep::running);
  ASSERT_TRUE(s.remote.battery.has_value());  // the status request on connect was answered
  EXPECT_EQ(*s.remote.battery, 0xc8);
  EXPECT_TRUE(s.problem.empty());

  rig.remote->send_ir(150, 500, 300, 2, -1);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  std::vector<LedSample> samples;
  ASSERT_EQ(device.drain(samples), 150u);
  std::vector<Nanos> ir_times;
  for (std::size_t i = 0; i < rig.remote->delivered.size(); ++i)
    if (rig.remote->delivered[i][0] == 0x33) ir_times.push_back(rig.remote->delivered_at[i]);
  ASSERT_EQ(ir_times.size(), 150u);
  EXPECT_EQ(samples[0].event, IrTrackerEvent::regained);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    ASSERT_TRUE(samples[i].has_point) << i;
    EXPECT_EQ(samples[i].t_ns, ir_times[i]) << i;  // the clock read when the report came in
    EXPECT_EQ(samples[i].point.t_ns, ir_times[i]) << i;
    EXPECT_EQ(samples[i].point.x, 500.0 + 2.0 * static_cast<double>(i)) << i;
    EXPECT_EQ(samples[i].point.y, 300.0 - static_cast<double>(i)) << i;
    EXPECT_EQ(samples[i].point.size, 3) << i;
    if (i > 0) {
      EXPECT_EQ(samples[i].event, IrTrackerEvent::none) << i;
    }
  }
  s = device.state();
  EXPECT_TRUE(s.tracking);
  EXPECT_DOUBLE_EQ(s.remote.ir_rate_hz, 100.0);  // 10 ms apart
  EXPECT_EQ(s.remote.ir_reports, 150u);
  EXPECT_EQ(device.drain(samples), 0u);  // drained once
}

TEST(WiimoteDevice, ASampleSinkGetsEverySampleOnTheReadingThreadInsteadOfTheQueue) {
  Rig rig;
  WiimoteDevice device(rig.finder, rig.clock);
  std::vector<LedSample> sunk;
  int calls = 0;
  Nanos last_now = 0;
  device.set_sample_sink([&](std::span<const LedSample> samples, Nanos now) {
    ++calls;
    EXPECT_GE(now, last_now);
    last_now = now;
    sunk.insert(sunk.end(), samples.begin(), samples.end());
  });
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  rig.remote->send_ir(20, 500, 300, 2, 0);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  ASSERT_EQ(sunk.size(), 20u);
  EXPECT_EQ(sunk[0].event, IrTrackerEvent::regained);
  EXPECT_EQ(sunk[19].point.x, 538.0);
  EXPECT_GT(calls, 20);  // every step, with or without samples: the sink's clock
  std::vector<LedSample> queued;
  EXPECT_EQ(device.drain(queued), 0u);
  // The remote vanishes: the sink hears `lost` from the step that dropped it.
  rig.remote->gone = true;
  ASSERT_TRUE(step_until(device, [&] { return device.state().link == LinkState::searching; }));
  EXPECT_EQ(sunk.back().event, IrTrackerEvent::lost);
}

//! Whether a register write (0x16) of `block` at 0xB00000 was sent.
bool wrote_block1(const FakeRemote& remote, const std::array<std::uint8_t, 9>& block) {
  for (const Bytes& b : remote.written)
    if (b.size() >= 15 && b[0] == 0x16 && b[2] == 0xb0 && b[3] == 0x00 && b[4] == 0x00 &&
        std::equal(block.begin(), block.end(), b.begin() + 6))
      return true;
  return false;
}

TEST(WiimoteDevice, ASensitivityRequestRerunsTheStartupWithItsBlocksAndKeepsThem) {
  Rig rig;
  WiimoteDevice device(rig.finder, rig.clock);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  const auto max = *find_sensitivity("max");
  EXPECT_FALSE(wrote_block1(*rig.remote, max.block1));
  EXPECT_FALSE(device.request_sensitivity("brightest"));
  ASSERT_TRUE(device.request_sensitivity("max"));
  device.step();
  ASSERT_TRUE(step_until(device, [&] { return device.state().startup == IrStartupStep::running; }));
  EXPECT_TRUE(wrote_block1(*rig.remote, max.block1));
  EXPECT_EQ(device.state().link, LinkState::running);  // the link stayed up
  EXPECT_EQ(device.state().connects, 1u);
  // A reconnection keeps the new blocks.
  rig.remote->written.clear();
  rig.remote->gone = true;
  ASSERT_TRUE(step_until(device, [&] { return !running(device); }));
  rig.remote->gone = false;
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  EXPECT_TRUE(wrote_block1(*rig.remote, max.block1));
}

TEST(WiimoteDevice, EveryFrameGivesASampleWithTheSlotsEvenWithoutADot) {
  Rig rig;
  WiimoteDeviceConfig config;
  config.every_frame = true;
  WiimoteDevice device(rig.finder, rig.clock, config);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  rig.remote->send(ir_report({}));
  rig.remote->send(ir_report({{500, 300, 3}, {100, 100, 2}}));
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  std::vector<LedSample> samples;
  ASSERT_EQ(device.drain(samples), 2u);
  EXPECT_TRUE(samples[0].has_frame);
  EXPECT_FALSE(samples[0].has_point);
  ASSERT_TRUE(samples[1].has_frame);
  EXPECT_TRUE(samples[1].has_point);
  ASSERT_TRUE(samples[1].frame.slots[1].has_value());
  EXPECT_EQ(samples[1].frame.slots[1]->x, 100);
}

TEST(WiimoteDevice, SilenceDropsTheRemoteThenItReconnectsAndRerunsTheStartup) {
  Rig rig;
  WiimoteDevice device(rig.finder, rig.clock);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  rig.remote->send_ir(20, 512, 384);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  const Nanos last_report = rig.remote->delivered_at.back();
  const std::size_t written_first = rig.remote->written.size();

  ASSERT_TRUE(step_until(device, [&] { return device.state().disconnects == 1; }));
  const Nanos dropped_at = rig.clock.now();
  EXPECT_GE(dropped_at - last_report, 3 * kNanosPerSecond);
  EXPECT_LE(dropped_at - last_report, 3 * kNanosPerSecond + 10 * kMs);  // one read's time-out
  WiimoteState s = device.state();
  EXPECT_EQ(s.link, LinkState::searching);
  EXPECT_NE(s.problem.find("no report for 3.0 s"), std::string::npos) << s.problem;
  EXPECT_FALSE(s.tracking);
  EXPECT_EQ(rig.remote->open_now, 0);  // closed
  std::vector<LedSample> samples;
  device.drain(samples);
  ASSERT_FALSE(samples.empty());
  EXPECT_EQ(samples.back().event, IrTrackerEvent::lost);
  // lost_after_ms (150), noticed within one read's time-out (10 ms).
  EXPECT_GE(samples.back().t_ns, last_report + 150 * kMs);
  EXPECT_LE(samples.back().t_ns, last_report + 160 * kMs);

  // The remote is back: the next attempt comes after the shortest back-off, and the
  // whole start-up is sent again on the new connection.
  const std::size_t enumerations = rig.finder.enumerated_at.size();
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  ASSERT_EQ(rig.finder.enumerated_at.size(), enumerations + 1);
  EXPECT_EQ(rig.finder.enumerated_at.back() - dropped_at, 500 * kMs);
  EXPECT_EQ(rig.remote->opens, 2);
  EXPECT_EQ(rig.remote->open_now, 1);
  const std::vector<Bytes> again(rig.remote->written.begin() + static_cast<std::ptrdiff_t>(written_first),
                                 rig.remote->written.end());
  EXPECT_EQ(again, connect_sequence());
  s = device.state();
  EXPECT_EQ(s.connects, 2u);
  EXPECT_TRUE(s.problem.empty());
  // Why it dropped stays said once it runs again (the kiosk tells a drop it did not see).
  EXPECT_NE(s.last_drop.find("no report for 3.0 s"), std::string::npos) << s.last_drop;

  rig.remote->send_ir(3, 100, 100);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  device.drain(samples);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[0].event, IrTrackerEvent::regained);
  EXPECT_EQ(samples[0].point.x, 100.0);
}

TEST(WiimoteDevice, BackOffDoublesFromHalfASecondToFiveAndNeverGivesUp) {
  FakeClock clock;
  FakeFinder finder(clock);  // no remote
  WiimoteDevice device(finder, clock);
  ASSERT_TRUE(step_until(device, [&] { return finder.enumerated_at.size() == 9; }));
  std::vector<Nanos> waits;
  for (std::size_t i = 1; i < finder.enumerated_at.size(); ++i)
    waits.push_back(finder.enumerated_at[i] - finder.enumerated_at[i - 1]);
  const std::vector<Nanos> expected = {500 * kMs, 1000 * kMs, 2000 * kMs, 4000 * kMs,
                                       5000 * kMs, 5000 * kMs, 5000 * kMs, 5000 * kMs};
  EXPECT_EQ(waits, expected);
  const WiimoteState s = device.state();
  EXPECT_EQ(s.link, LinkState::searching);
  EXPECT_EQ(s.failed_attempts, 9u);
  EXPECT_NE(s.problem.find("no Wii Remote found"), std::string::npos) << s.problem;
  EXPECT_GT(clock.sleeps(), 0);  // it waited through the clock, not by spinning

  // Plugged in at last: found at the next attempt, at most 5 s later.
  const Nanos plugged = clock.now();
  finder.add("/dev/hidraw0");
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  EXPECT_LE(finder.enumerated_at.back() - plugged, 5 * kNanosPerSecond);
}

TEST(WiimoteDevice, OpenFailureIsReportedAndRetried) {
  Rig rig;
  rig.finder.open_errors["/dev/hidraw3"] = "cannot open the Wii Remote at /dev/hidraw3 (Permission denied); hint";
  WiimoteDevice device(rig.finder, rig.clock);
  ASSERT_TRUE(step_until(device, [&] { return rig.finder.opened.size() == 3; }));
  WiimoteState s = device.state();
  EXPECT_EQ(s.link, LinkState::searching);
  EXPECT_EQ(s.problem, "cannot open the Wii Remote at /dev/hidraw3 (Permission denied); hint");
  EXPECT_EQ(s.failed_attempts, 3u);
  EXPECT_EQ(s.connects, 0u);
  rig.finder.open_errors.clear();  // the udev rule was installed
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  EXPECT_EQ(device.state().connects, 1u);
}

TEST(WiimoteDevice, AStatusReportResetsTheModeSo0x12IsSentAgain) {
  Rig rig;
  WiimoteDevice device(rig.finder, rig.clock);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  rig.remote->send_ir(5, 400, 400);
  rig.remote->send(status_report(0x40, /*low=*/true));  // unsolicited: battery low
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  const std::size_t n = rig.remote->written.size();
  ASSERT_GE(n, 1u);
  EXPECT_EQ(rig.remote->written.back(), (Bytes{0x12, 0x06, 0x33}));
  EXPECT_EQ(rig.remote->count_written(0x12), 2);
  WiimoteState s = device.state();
  EXPECT_EQ(s.mode_resets, 1u);
  EXPECT_EQ(*s.remote.battery, 0x40);
  EXPECT_TRUE(s.remote.battery_low);
  // The 0x12 is acknowledged and IR flows again, without a reconnect.
  rig.remote->send_ir(5, 402, 400);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  s = device.state();
  EXPECT_EQ(s.link, LinkState::running);
  EXPECT_EQ(s.connects, 1u);
  EXPECT_EQ(s.remote.ir_reports, 10u);
  EXPECT_EQ(s.point->x, 402.0);
}

TEST(WiimoteDevice, RumblePulseSetsTheBitInEveryReportThenClearsIt) {
  Rig rig;
  WiimoteDeviceConfig config;
  config.rumble_ns = 40 * kMs;
  WiimoteDevice device(rig.finder, rig.clock, config);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  device.on_impact();  // rumble_on_impact is off by default: nothing
  device.step();
  const std::size_t n = rig.remote->written.size();
  EXPECT_EQ(rig.remote->written.back(), (Bytes{0x12, 0x06, 0x33}));

  device.pulse_rumble();
  device.step();
  ASSERT_EQ(rig.remote->written.size(), n + 1);
  EXPECT_EQ(rig.remote->written[n], (Bytes{0x11, 0x11}));  // LED 1 + rumble
  EXPECT_TRUE(device.state().rumbling);
  const Nanos started = rig.clock.now();
  // A status report while it rumbles: the 0x12 sent again carries the rumble bit too.
  rig.remote->send(status_report(), 5 * kMs);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->count_written(0x12) == 2; }));
  EXPECT_EQ(rig.remote->written.back(), (Bytes{0x12, 0x07, 0x33}));
  ASSERT_TRUE(step_until(device, [&] { return !device.state().rumbling; }));
  const Nanos stopped = rig.clock.now();
  EXPECT_EQ(rig.remote->written.back(), (Bytes{0x11, 0x10}));  // motor off, LED kept
  EXPECT_GE(stopped - started, 40 * kMs - 10 * kMs);
  EXPECT_LE(stopped - started, 40 * kMs + 10 * kMs);  // within one read's time-out
  EXPECT_EQ(device.state().rumble_pulses, 1u);
  const Bytes mode_while_rumbling = {0x12, 0x07, 0x33};
  for (const Bytes& b : rig.remote->written) {
    if (b[0] == 0x11) continue;
    EXPECT_EQ(b[1] & 0x01, b == mode_while_rumbling ? 1 : 0) << static_cast<int>(b[0]);
  }
}

TEST(WiimoteDevice, RumbleOnImpactOnlyWhenConfigured) {
  Rig rig;
  WiimoteDeviceConfig config;
  config.rumble_on_impact = true;
  WiimoteDevice device(rig.finder, rig.clock, config);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  device.on_impact();
  device.step();
  EXPECT_EQ(rig.remote->written.back(), (Bytes{0x11, 0x11}));
}

TEST(WiimoteDevice, AVanishedDeviceIsDroppedAtOnce) {
  Rig rig;
  WiimoteDevice device(rig.finder, rig.clock);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  rig.remote->send_ir(3, 300, 300);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  const Nanos before = rig.clock.now();
  rig.remote->gone = true;
  device.step();
  const WiimoteState s = device.state();
  EXPECT_EQ(s.link, LinkState::searching);
  EXPECT_EQ(s.disconnects, 1u);
  EXPECT_NE(s.problem.find("gone"), std::string::npos) << s.problem;
  EXPECT_EQ(rig.clock.now(), before);  // no time-out waited for
  EXPECT_EQ(rig.remote->open_now, 0);
  std::vector<LedSample> samples;
  device.drain(samples);
  ASSERT_FALSE(samples.empty());
  EXPECT_EQ(samples.back().event, IrTrackerEvent::lost);
}

TEST(WiimoteDevice, AFailedStartupClosesAndTriesAgain) {
  Rig rig;
  rig.remote->answers = false;  // ignores everything
  WiimoteDevice device(rig.finder, rig.clock);
  ASSERT_TRUE(step_until(device, [&] { return device.state().disconnects == 1; }));
  WiimoteState s = device.state();
  EXPECT_EQ(s.problem,
            "IR start-up: no acknowledgement for IR pixel clock (0x13) after 4 tries, 100 ms apart "
            "(is the remote still connected?)");
  EXPECT_EQ(rig.remote->count_written(0x13), 4);
  rig.remote->answers = true;
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  EXPECT_EQ(rig.remote->count_written(0x13), 5);
  EXPECT_EQ(device.state().connects, 2u);
}

TEST(WiimoteDevice, TheConfiguredRemoteIsChosen) {
  FakeClock clock;
  FakeFinder finder(clock);
  finder.add("/dev/hidraw1", "00:1f:32:11:22:33");
  finder.add("/dev/hidraw2", "00:1f:32:aa:bb:cc", kWiiRemoteTrProductId);
  WiimoteDeviceConfig config;
  config.device = "AA:BB";  // case-insensitive part of the serial
  WiimoteDevice device(finder, clock, config);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  EXPECT_EQ(finder.opened, std::vector<std::string>{"/dev/hidraw2"});
  EXPECT_EQ(device.state().device.product_id, kWiiRemoteTrProductId);

  config.device = "hidraw9";
  WiimoteDevice other(finder, clock, config);
  other.step();
  EXPECT_NE(other.state().problem.find("no Wii Remote matches \"hidraw9\" (2 seen"), std::string::npos)
      << other.state().problem;
}

TEST(WiimoteDevice, RawReportsAreKeptForRecordingWithTheirTimes) {
  Rig rig;
  WiimoteDeviceConfig config;
  config.keep_raw_reports = true;
  config.queue_capacity = 10;
  WiimoteDevice device(rig.finder, rig.clock, config);
  ASSERT_TRUE(step_until(device, [&] { return running(device); }));
  std::vector<RawReport> raw;
  device.drain_raw(raw);
  const std::size_t k = rig.remote->delivered.size();  // the status answer and 8 acks
  ASSERT_EQ(k, 9u);
  ASSERT_EQ(raw.size(), k);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    EXPECT_EQ(Bytes(raw[i].span().begin(), raw[i].span().end()), rig.remote->delivered[i]) << i;
    EXPECT_EQ(raw[i].t_ns, rig.remote->delivered_at[i]) << i;
  }
  // A consumer that does not drain in time loses the newest, counted; the reader never waits.
  rig.remote->send_ir(12, 200, 200);
  ASSERT_TRUE(step_until(device, [&] { return rig.remote->script.empty(); }));
  EXPECT_EQ(device.drain_raw(raw), 10u);
  EXPECT_EQ(raw.back().t_ns, rig.remote->delivered_at[k + 9]);
  std::vector<LedSample> samples;
  EXPECT_EQ(device.drain(samples), 10u);
  EXPECT_EQ(samples.back().point.t_ns, rig.remote->delivered_at[k + 9]);
  EXPECT_EQ(device.state().dropped, 2u + 2u);  // 12 raw reports and 12 samples into 10 places each
}

TEST(WiimoteDevice, TheReadingThreadDeliversSamplesAndStops) {
  Rig rig;
  rig.remote->send_ir(50, 600, 200, 1, 0);
  WiimoteDevice device(rig.finder, rig.clock);
  device.start();
  std::vector<LedSample> all, some;
  // Bounded by a count of polls, not by a measured time.
  for (int i = 0; i < 5000 && all.size() < 50; ++i) {
    device.drain(some);
    all.insert(all.end(), some.begin(), some.end());
    if (all.size() < 50) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  device.stop();
  device.drain(some);
  all.insert(all.end(), some.begin(), some.end());
  ASSERT_GE(all.size(), 50u);
  EXPECT_EQ(all[0].event, IrTrackerEvent::regained);
  for (std::size_t i = 0; i < 50; ++i) EXPECT_EQ(all[i].point.x, 600.0 + static_cast<double>(i)) << i;
  EXPECT_EQ(rig.remote->open_now, 0);  // stop() closed it
}

TEST(WiimoteDevice, SettingsFileValuesBecomeTheDeviceConfig) {
  AppConfig app;
  app.wiimote.device = "hidraw4";
  app.wiimote.ir_mode = IrMode::basic;
  app.wiimote.sensitivity = "max";
  app.wiimote.rumble_on_impact = true;
  app.wiimote.rumble_ms = 25;
  app.wiimote.silence_timeout_ms = 1500;
  app.wiimote.reconnect_min_ms = 200;
  app.wiimote.reconnect_max_ms = 800;
  app.tracking.lost_after_ms = 90;
  const WiimoteDeviceConfig c = device_config(app);
  EXPECT_EQ(c.device, "hidraw4");
  EXPECT_EQ(c.ir.mode, IrMode::basic);
  EXPECT_EQ(c.ir.sensitivity.name, "max");
  EXPECT_TRUE(c.rumble_on_impact);
  EXPECT_EQ(c.rumble_ns, 25 * kMs);
  EXPECT_EQ(c.silence_timeout_ns, 1500 * kMs);
  EXPECT_EQ(c.reconnect_min_ns, 200 * kMs);
  EXPECT_EQ(c.reconnect_max_ns, 800 * kMs);
  EXPECT_EQ(c.tracking.lost_after_ms, 90.0);
  app.wiimote.sensitivity = "nonsense";  // only a hand-built config can hold it
  EXPECT_EQ(device_config(app).ir.sensitivity.name, "wii3");
}

}  // namespace
}  // namespace mallet::input::wiimote
