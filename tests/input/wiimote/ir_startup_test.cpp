// The IR camera's start-up sequence against a scripted fake remote: the state machine is
// fed times and reports by hand, and what it asks to send is checked byte for byte.
#include "input/wiimote/ir_startup.hpp"

#include <gtest/gtest.h>

namespace mallet::input::wiimote {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr Nanos kMs = 1'000'000;

Bytes write_reg(std::uint32_t address, Bytes data, std::uint8_t flags = 0x04) {
  Bytes b = {0x16, flags, static_cast<std::uint8_t>(address >> 16), static_cast<std::uint8_t>(address >> 8),
             static_cast<std::uint8_t>(address), static_cast<std::uint8_t>(data.size())};
  b.insert(b.end(), data.begin(), data.end());
  b.resize(22, 0x00);
  return b;
}

//! The Linux driver's sequence for extended mode with its sensitivity ("wii3").
std::vector<Bytes> linux_sequence() {
  return {
      {0x13, 0x06},
      {0x1a, 0x06},
      write_reg(0xb00030, {0x01}),
      write_reg(0xb00000, {0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xaa, 0x00, 0x64}),
      write_reg(0xb0001a, {0x63, 0x03}),
      write_reg(0xb00033, {0x03}),
      write_reg(0xb00030, {0x08}),
      {0x12, 0x06, 0x33},
  };
}

Bytes ack(std::uint8_t report, std::uint8_t error = 0) { return {0x22, 0x00, 0x00, report, error}; }
const Bytes kStatus = {0x20, 0x00, 0x00, 0x08, 0x00, 0x00, 0xc8};

std::vector<Bytes> drain(IrStartup& s) {
  std::vector<Bytes> out;
  while (auto r = s.poll()) out.push_back(r->vector());
  return out;
}

//! A remote that acknowledges each report it is sent, with `error` for the n-th and for
//! every copy of it sent again (a write it cannot do).
struct StartupRemote {
  int refuse_index = -1;  //!< which report gets an error ack (-1: none)
  std::uint8_t error = 0x03;
  int drop_index = -1;    //!< which report's ack is lost once
  std::vector<Bytes> received;

  //! Sends everything `s` has queued to the fake and feeds its answers back.
  void exchange(IrStartup& s, Nanos now_ns) {
    for (bool more = true; more;) {
      more = false;
      while (auto r = s.poll()) {
        received.push_back(r->vector());
        const int index = static_cast<int>(received.size()) - 1;
        if (index == drop_index) continue;
        if (r->requests_ack() || r->id() == OutputReportId::write_memory) {
          const bool refused = refuse_index >= 0 && index >= refuse_index && received.back() == received[refuse_index];
          s.feed(ack(r->bytes[0], refused ? error : 0), now_ns);
          more = true;
        }
      }
    }
  }
};

TEST(IrStartup, SendsTheLinuxSequenceOneAckAtATime) {
  IrStartup s;
  EXPECT_EQ(s.step(), IrStartupStep::idle);
  EXPECT_FALSE(s.poll());
  s.start(0);
  const auto expected = linux_sequence();
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto sent = drain(s);
    ASSERT_EQ(sent.size(), 1u) << "step " << i;
    EXPECT_EQ(sent[0], expected[i]) << "step " << i;
    EXPECT_FALSE(s.running());
    s.tick(static_cast<Nanos>(i) * kMs);  // well within the timeout: nothing resent
    EXPECT_TRUE(drain(s).empty());
    s.feed(ack(sent[0][0]), static_cast<Nanos>(i) * kMs);
  }
  EXPECT_TRUE(s.running());
  EXPECT_TRUE(drain(s).empty());
  EXPECT_EQ(s.resends(), 0);
  s.tick(10 * kNanosPerSecond);  // running: no timers
  EXPECT_TRUE(drain(s).empty());
}

TEST(IrStartup, BasicModeMaxSensitivityAndRumble) {
  IrStartupConfig c;
  c.mode = IrMode::basic;
  c.sensitivity = *find_sensitivity("max");
  c.rumble = Rumble::on;
  IrStartup s(c);
  StartupRemote remote;
  s.start(0);
  remote.exchange(s, 0);
  ASSERT_TRUE(s.running()) << s.error();
  const std::vector<Bytes> expected = {
      {0x13, 0x07},
      {0x1a, 0x07},
      write_reg(0xb00030, {0x01}, 0x05),
      write_reg(0xb00000, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x90, 0x00, 0x41}, 0x05),
      write_reg(0xb0001a, {0x40, 0x00}, 0x05),
      write_reg(0xb00033, {0x01}, 0x05),
      write_reg(0xb00030, {0x08}, 0x05),
      {0x12, 0x07, 0x36},
  };
  EXPECT_EQ(remote.received, expected);
}

TEST(IrStartup, AStepRefusedOnEveryTryFailsWithTheStepNamed) {
  IrStartup s;  // 3 resends: 4 tries
  s.start(0);
  for (int step = 0; step < 3; ++step) {  // pixel clock, logic, camera on
    ASSERT_EQ(drain(s).size(), 1u);
    s.feed(ack(step == 0 ? 0x13 : step == 1 ? 0x1a : 0x16), 0);
  }
  for (int attempt = 1; attempt <= 4; ++attempt) {  // sensitivity block 1, refused each time
    const std::vector<Bytes> sent = drain(s);
    ASSERT_EQ(sent.size(), 1u) << "try " << attempt;
    EXPECT_EQ(sent[0][0], 0x16);
    EXPECT_FALSE(s.failed()) << "try " << attempt;
    s.feed(ack(0x16, 3), 0);
  }
  EXPECT_TRUE(s.failed());
  EXPECT_EQ(s.resends(), 3);
  EXPECT_EQ(s.error(),
            "IR start-up: the remote refused sensitivity block 1 (write 9 bytes at 0xb00000) "
            "(acknowledgement error code 3)");
  s.tick(kNanosPerSecond);
  EXPECT_TRUE(drain(s).empty());
}

TEST(IrStartup, TheKernelsRefusedWriteIsNotTakenForOurs) {
  // hid-wiimote probes the absent Motion Plus with a write that the remote refuses (error
  // 7); its ack, also for report 0x16, arrives while our camera write waits for its own.
  IrStartup s;
  s.start(0);
  ASSERT_EQ(drain(s).size(), 1u);
  s.feed(ack(0x13), 0);
  ASSERT_EQ(drain(s).size(), 1u);
  s.feed(ack(0x1a), 0);
  const std::vector<Bytes> camera_on = drain(s);
  ASSERT_EQ(camera_on.size(), 1u);
  s.feed(ack(0x16, 7), 1);  // the kernel's refused probe
  EXPECT_FALSE(s.failed());
  EXPECT_EQ(s.step(), IrStartupStep::camera_on);
  EXPECT_EQ(drain(s), camera_on);  // ours again, at once
  s.feed(ack(0x16), 2);            // the remote's answer to ours
  EXPECT_EQ(s.step(), IrStartupStep::sensitivity1);
}

TEST(IrStartup, AcksForOtherReportsAreNotOurs) {
  IrStartup s;
  s.start(0);
  ASSERT_EQ(drain(s).size(), 1u);
  s.feed(ack(0x11), 1);     // the transport's LED report
  s.feed(ack(0x16, 3), 1);  // some write of someone else's, even refused
  EXPECT_EQ(s.step(), IrStartupStep::pixel_clock);
  EXPECT_FALSE(s.failed());
  s.feed(ack(0x13), 2);
  EXPECT_EQ(s.step(), IrStartupStep::logic);
}

TEST(IrStartup, LostAckIsResentAfterTheTimeout) {
  IrStartup s;  // 100 ms, 3 resends
  s.start(1000);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x13, 0x06}}));
  s.feed(ack(0x13), 1000);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x1a, 0x06}}));
  // The 0x1a ack is lost.
  s.tick(1000 + 99 * kMs);
  EXPECT_TRUE(drain(s).empty());
  s.tick(1000 + 100 * kMs);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x1a, 0x06}}));
  EXPECT_EQ(s.resends(), 1);
  s.feed(ack(0x1a), 1000 + 150 * kMs);
  EXPECT_EQ(s.step(), IrStartupStep::camera_on);
  StartupRemote remote;
  remote.exchange(s, 1000 + 150 * kMs);
  EXPECT_TRUE(s.running());
}

TEST(IrStartup, RetriesRunOutWithAClearError) {
  IrStartupConfig c;
  c.ack_timeout_ns = 50 * kMs;
  c.max_resends = 2;
  IrStartup s(c);
  s.start(0);
  StartupRemote remote;
  remote.exchange(s, 0);  // would run to the end: start over and stay silent instead
  s.start(0);
  EXPECT_EQ(drain(s).size(), 1u);
  for (Nanos t = 0; t <= 400 * kMs; t += 10 * kMs) {
    s.tick(t);
    for (const auto& r : drain(s)) EXPECT_EQ(r, (Bytes{0x13, 0x06})) << t;
    if (s.failed()) {
      EXPECT_EQ(t, 150 * kMs);  // sent at 0, 50, 100; silent until 150
      break;
    }
  }
  ASSERT_TRUE(s.failed());
  EXPECT_EQ(s.resends(), 2);
  EXPECT_EQ(s.error(),
            "IR start-up: no acknowledgement for IR pixel clock (0x13) after 3 tries, 50 ms apart "
            "(is the remote still connected?)");
}

TEST(IrStartup, RestartsFromTheTopAfterAReconnect) {
  IrStartup s;
  StartupRemote remote;
  s.start(0);
  remote.exchange(s, 0);
  ASSERT_TRUE(s.running());
  // The remote dropped and came back: it forgot everything.
  s.start(5 * kNanosPerSecond);
  EXPECT_EQ(s.step(), IrStartupStep::pixel_clock);
  StartupRemote again;
  again.exchange(s, 5 * kNanosPerSecond);
  EXPECT_TRUE(s.running());
  EXPECT_EQ(again.received, linux_sequence());
  // And after a failure.
  StartupRemote refusing;
  refusing.refuse_index = 0;
  s.start(6 * kNanosPerSecond);
  refusing.exchange(s, 6 * kNanosPerSecond);
  ASSERT_TRUE(s.failed());
  s.start(7 * kNanosPerSecond);
  EXPECT_TRUE(s.error().empty());
  StartupRemote fine;
  fine.exchange(s, 7 * kNanosPerSecond);
  EXPECT_TRUE(s.running());
  // reset(): idle, nothing queued.
  s.start(8 * kNanosPerSecond);
  s.reset();
  EXPECT_EQ(s.step(), IrStartupStep::idle);
  EXPECT_FALSE(s.poll());
}

TEST(IrStartup, StatusReportWhileRunningResendsTheReportingMode) {
  IrStartup s;
  StartupRemote remote;
  s.start(0);
  remote.exchange(s, 0);
  ASSERT_TRUE(s.running());
  s.feed(kStatus, kNanosPerSecond);  // e.g. an extension was plugged in
  EXPECT_EQ(s.step(), IrStartupStep::reporting_mode);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x12, 0x06, 0x33}}));
  EXPECT_EQ(s.mode_resets(), 1);
  // Its ack can be lost too.
  s.tick(kNanosPerSecond + 100 * kMs);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x12, 0x06, 0x33}}));
  s.feed(ack(0x12), kNanosPerSecond + 120 * kMs);
  EXPECT_TRUE(s.running());
}

TEST(IrStartup, StatusReportDuringTheSequence) {
  IrStartup s;
  s.start(0);
  drain(s);
  s.feed(kStatus, 1);  // before 0x12: nothing to redo, it comes at the end
  EXPECT_TRUE(drain(s).empty());
  EXPECT_EQ(s.step(), IrStartupStep::pixel_clock);
  for (int id : {0x13, 0x1a, 0x16, 0x16, 0x16, 0x16, 0x16}) s.feed(ack(static_cast<std::uint8_t>(id)), 2);
  EXPECT_EQ(drain(s).size(), 7u);
  ASSERT_EQ(s.step(), IrStartupStep::reporting_mode);
  // A status report while 0x12 waits for its ack: the mode may have been reset after
  // it was applied, so it goes out again at once.
  s.feed(kStatus, 3);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x12, 0x06, 0x33}}));
  s.feed(ack(0x12), 4);
  EXPECT_TRUE(s.running());
  s.feed(ack(0x12), 5);  // the second ack changes nothing
  EXPECT_TRUE(s.running());
  EXPECT_TRUE(drain(s).empty());
}

TEST(IrStartup, GarbageAndDataReportsAreIgnored) {
  IrStartup s;
  s.start(0);
  drain(s);
  s.feed(Bytes{}, 1);
  s.feed(Bytes{0x22, 0x00}, 1);  // a truncated ack is no ack
  s.feed(Bytes{0x99, 1, 2, 3}, 1);
  Bytes ir(18, 0xff);
  ir[0] = 0x33;
  s.feed(ir, 1);
  EXPECT_EQ(s.step(), IrStartupStep::pixel_clock);
  EXPECT_EQ(s.ignored_reports(), 3);
  EXPECT_TRUE(drain(s).empty());
}

TEST(IrStartup, RumbleChangesApplyToResends) {
  IrStartup s;
  s.start(0);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x13, 0x06}}));
  s.set_rumble(Rumble::on);
  s.tick(100 * kMs);
  EXPECT_EQ(drain(s), (std::vector<Bytes>{{0x13, 0x07}}));
}

TEST(IrStartup, SensitivityPresetsByName) {
  const auto wii3 = find_sensitivity(kDefaultSensitivity);
  ASSERT_TRUE(wii3);
  EXPECT_EQ(wii3->block1, (std::array<std::uint8_t, 9>{0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xaa, 0x00, 0x64}));
  EXPECT_EQ(wii3->block2, (std::array<std::uint8_t, 2>{0x63, 0x03}));
  EXPECT_EQ(IrStartupConfig{}.sensitivity.name, "wii3");
  const auto wii1 = find_sensitivity("wii1");
  ASSERT_TRUE(wii1);
  EXPECT_EQ(wii1->block2, (std::array<std::uint8_t, 2>{0xfd, 0x05}));
  const auto wii5 = find_sensitivity("wii5");
  ASSERT_TRUE(wii5);
  EXPECT_EQ(wii5->block1[0], 0x07);
  const auto marcan = find_sensitivity("marcan");
  ASSERT_TRUE(marcan);
  EXPECT_EQ(marcan->block1[8], 0xc0);
  EXPECT_FALSE(find_sensitivity("WII3"));
  EXPECT_FALSE(find_sensitivity("wii6"));
  EXPECT_EQ(sensitivity_names(), "wii1, wii2, wii3, wii4, wii5, marcan, max");
}

}  // namespace
}  // namespace mallet::input::wiimote
