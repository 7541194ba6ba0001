// The real hidapi transport (src/input/wiimote/hid_transport.cpp), linked against the fake
// hidapi of tests/input/fake_hidapi instead of libhidapi-hidraw: enumeration keeps only
// the two Wii Remote products, a failed open names the udev rule, bytes pass unchanged
// both ways, and the whole device logic runs over it (start-up, silence → reconnect with
// back-off and a fresh start-up, 0x20 → 0x12, rumble), ending in a recording whose replay
// shows the same dots as `mallet wiimote decode`.
#include "input/wiimote/hid_transport.hpp"

#include <cerrno>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "run_cli.hpp"
#include "fake_hidapi.hpp"
#include "input/wiimote/replay_source.hpp"
#include "input/wiimote/wiimote_device.hpp"
#include "test_paths.hpp"
#include "wiimote/wiimote_test_support.hpp"

namespace mallet::input::wiimote {
namespace {

using namespace test;

const std::string kPath = "/dev/hidraw5";

class HidTransportTest : public ::testing::Test {
 protected:
  void SetUp() override { fake_hidapi::reset(); }
  void TearDown() override { fake_hidapi::reset(); }

  //! A remote that answers like a real one, on a clock that advances by each read's
  //! time-out when nothing comes and by 1 ms per report.
  void add_remote(const std::string& path = kPath) {
    fake_hidapi::add_device({path, kNintendoVendorId, kWiiRemoteProductId, L"00:1f:32:aa:bb:cc", L"Nintendo RVL-CNT-01"});
    fake_hidapi::set_answers(path, true);
    fake_hidapi::set_read_hook([this](int timeout_ms, int result) {
      clock.advance(result == 0 ? Nanos{timeout_ms} * kMs : 1 * kMs);
    });
  }

  std::vector<Bytes> writes(const std::string& path = kPath) {
    std::vector<Bytes> out;
    for (const auto& w : fake_hidapi::writes(path)) out.emplace_back(w.begin(), w.end());
    return out;
  }

  FakeClock clock;
};

bool step_until(WiimoteDevice& device, const std::function<bool()>& done, int max_steps = 100'000) {
  for (int i = 0; i < max_steps && !done(); ++i) device.step();
  return done();
}

TEST_F(HidTransportTest, EnumerationKeepsOnlyTheTwoWiiRemoteProducts) {
  fake_hidapi::add_device({"/dev/hidraw1", 0x057e, 0x0306, L"00:1f:32:00:00:01", L"Nintendo RVL-CNT-01"});
  fake_hidapi::add_device({"/dev/hidraw2", 0x057e, 0x0337, L"", L"WUP-028"});  // GameCube adapter
  fake_hidapi::add_device({"/dev/hidraw3", 0x046d, 0xc52b, L"", L"USB Receiver"});
  fake_hidapi::add_device({"/dev/hidraw4", 0x057e, 0x0330, L"00:1f:32:00:00:02", L"Nintendo RVL-CNT-01-TR \u00e9"});
  const std::vector<HidDeviceInfo> seen = HidTransport::enumerate();
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], (HidDeviceInfo{"/dev/hidraw1", 0x057e, 0x0306, "00:1f:32:00:00:01", "Nintendo RVL-CNT-01"}));
  EXPECT_EQ(seen[1], (HidDeviceInfo{"/dev/hidraw4", 0x057e, 0x0330, "00:1f:32:00:00:02",
                                    "Nintendo RVL-CNT-01-TR \xc3\xa9"}));  // UTF-8
  // One call, for Nintendo's vendor id and any product: the product list is ours.
  EXPECT_EQ(fake_hidapi::enumerate_calls(), (std::vector<std::pair<unsigned short, unsigned short>>{{0x057e, 0}}));
  EXPECT_EQ(HidDeviceFinder().enumerate(), seen);
}

TEST_F(HidTransportTest, AFailedOpenNamesThePathTheReasonAndTheUdevRule) {
  add_remote();
  fake_hidapi::fail_open(kPath, EACCES, L"Permission denied");
  const OpenResult r = HidTransport::open(kPath);
  EXPECT_FALSE(r.transport);
  EXPECT_NE(r.error.find("cannot open the Wii Remote at /dev/hidraw5 (Permission denied)"), std::string::npos) << r.error;
  // The packaged rule's file, and how to install the same rule by hand without the package.
  EXPECT_NE(r.error.find("the mallet package installs the udev rule /usr/lib/udev/rules.d/70-mallet-wiimote.rules"),
            std::string::npos)
      << r.error;
  EXPECT_NE(r.error.find("create /etc/udev/rules.d/70-mallet-wiimote.rules"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(R"(KERNEL=="hidraw*", KERNELS=="*:057E:0306.*|*:057E:0330.*", TAG+="uaccess")"),
            std::string::npos)
      << r.error;
  EXPECT_NE(r.error.find("udevadm control --reload && sudo udevadm trigger"), std::string::npos) << r.error;
  EXPECT_EQ(fake_hidapi::open_count(), 0);

  const OpenResult missing = HidTransport::open("/dev/hidraw99");
  EXPECT_FALSE(missing.transport);
  EXPECT_NE(missing.error.find("/dev/hidraw99 (No such file or directory)"), std::string::npos) << missing.error;
}

TEST_F(HidTransportTest, BytesPassUnchangedAndTheDeviceIsClosedOnce) {
  add_remote();
  fake_hidapi::set_answers(kPath, false);
  {
    OpenResult r = HidTransport::open(kPath);
    ASSERT_TRUE(r.transport) << r.error;
    EXPECT_EQ(fake_hidapi::open_count(), 1);
    Transport& t = *r.transport;
    EXPECT_TRUE(t.write(Bytes{0x11, 0x10}));
    EXPECT_TRUE(t.write(Bytes{0x12, 0x04, 0x33}));
    EXPECT_EQ(writes(), (std::vector<Bytes>{{0x11, 0x10}, {0x12, 0x04, 0x33}}));

    const Bytes report = ir_report({{1, 2, 3}});
    fake_hidapi::push_report(kPath, report);
    std::array<std::uint8_t, 64> buffer{};
    ASSERT_EQ(t.read(buffer, 10), static_cast<int>(report.size()));
    EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(report.size())), report);
    const Nanos before = clock.now();
    EXPECT_EQ(t.read(buffer, 10), 0);  // time-out
    EXPECT_EQ(clock.now() - before, 10 * kMs);

    fake_hidapi::gone_after_reads(kPath, 0);
    EXPECT_EQ(t.read(buffer, 10), -1);
    EXPECT_FALSE(t.write(Bytes{0x15, 0x00}));
  }
  EXPECT_EQ(fake_hidapi::open_count(), 0);
  EXPECT_EQ(fake_hidapi::close_count(), 1);
}

TEST_F(HidTransportTest, TheDeviceRunsOverHidapiAndReconnectsAfterSilenceWithAFreshStartup) {
  add_remote();
  HidDeviceFinder finder;
  WiimoteDevice device(finder, clock);
  ASSERT_TRUE(step_until(device, [&] { return device.state().link == LinkState::running; }));
  EXPECT_EQ(writes(), connect_sequence());
  for (int i = 0; i < 10; ++i) fake_hidapi::push_report(kPath, ir_report({{300 + i, 200, 4}}));
  std::vector<LedSample> samples;
  ASSERT_TRUE(step_until(device, [&] { return device.state().remote.ir_reports == 10; }));
  device.drain(samples);
  ASSERT_EQ(samples.size(), 10u);
  EXPECT_EQ(samples[9].point.x, 309.0);

  // Silence: dropped after 3 s, reopened 0.5 s later, the start-up sent again.
  ASSERT_TRUE(step_until(device, [&] { return device.state().disconnects == 1; }));
  const Nanos dropped = clock.now();
  EXPECT_EQ(fake_hidapi::open_count(), 0);
  ASSERT_TRUE(step_until(device, [&] { return device.state().connects == 2; }));
  EXPECT_EQ(clock.now() - dropped, 500 * kMs);
  ASSERT_TRUE(step_until(device, [&] { return device.state().link == LinkState::running; }));
  std::vector<Bytes> expected = connect_sequence();
  const std::vector<Bytes> again = connect_sequence();
  expected.insert(expected.end(), again.begin(), again.end());
  EXPECT_EQ(writes(), expected);
  EXPECT_EQ(fake_hidapi::open_count(), 1);
  EXPECT_EQ(fake_hidapi::close_count(), 1);

  // The node vanishes: dropped at once, then searched for with the back-off (the node is
  // still listed, so it is reopened and the start-up is tried again).
  fake_hidapi::gone_after_reads(kPath, 0);
  device.step();
  EXPECT_EQ(device.state().disconnects, 2u);
  EXPECT_NE(device.state().problem.find("gone"), std::string::npos) << device.state().problem;
}

TEST_F(HidTransportTest, StatusReportResendsTheModeAndRumbleSetsBitZero) {
  add_remote();
  HidDeviceFinder finder;
  WiimoteDeviceConfig config;
  config.rumble_on_impact = true;
  WiimoteDevice device(finder, clock, config);
  ASSERT_TRUE(step_until(device, [&] { return device.state().link == LinkState::running; }));
  const std::size_t n = writes().size();

  fake_hidapi::push_report(kPath, status_report(0x55));
  ASSERT_TRUE(step_until(device, [&] { return writes().size() == n + 1; }));
  EXPECT_EQ(writes().back(), (Bytes{0x12, 0x06, 0x33}));
  EXPECT_EQ(device.state().mode_resets, 1u);

  device.on_impact();
  device.step();
  EXPECT_EQ(writes()[n + 1], (Bytes{0x11, 0x11}));
  ASSERT_TRUE(step_until(device, [&] { return !device.state().rumbling; }));
  EXPECT_EQ(writes().back(), (Bytes{0x11, 0x10}));
}

TEST_F(HidTransportTest, ARecordingOfTheLiveRemoteReplaysToTheDotsDecodePrints) {
  add_remote();
  std::vector<Bytes> ir = {
      ir_report({{512, 384, 3}, {40, 700, 1}}),
      ir_report({{513, 385, 3}}),
      ir_report({{0, 0, 0}, {1023, 767, 15}, {1, 766, 7}, {600, 10, 2}}),
      ir_report({}),
      Bytes{0x36, 0x00, 0x00, 0xff, 0xff, 0xb9, 0x2c, 0xbc, 0xff, 0xff, 0xf0, 0x01, 0x02, 0, 0, 0, 0, 0, 0, 0, 0, 0},
  };
  HidDeviceFinder finder;
  WiimoteDeviceConfig config;
  config.keep_raw_reports = true;
  WiimoteDevice device(finder, clock, config);
  ASSERT_TRUE(step_until(device, [&] { return device.state().link == LinkState::running; }));
  for (const Bytes& b : ir) fake_hidapi::push_report(kPath, b);
  ASSERT_TRUE(step_until(device, [&] { return device.state().remote.ir_reports == ir.size(); }));

  const auto dir = mallet::test::scratch_dir();
  {
    std::ofstream out(dir / "live.replay");
    ReplayWriter writer(out);
    std::vector<RawReport> raw;
    device.drain_raw(raw);
    for (const RawReport& r : raw) writer.write(r.t_ns, r.span());
  }
  std::string hex;
  for (const Bytes& b : ir) hex += to_hex(b) + "\n";
  std::ofstream(dir / "ir.hex") << hex;

  ReplaySource replay = ReplaySource::open(dir / "live.replay");
  std::string dots;
  while (auto o = replay.next())
    if (o->frame) dots += format_ir_slots(o->frame->slots) + "\n";
  const auto decoded = mallet::test::run_mallet("wiimote decode --hex " + (dir / "ir.hex").string());
  ASSERT_EQ(decoded.status, 0) << decoded.output;
  EXPECT_EQ(dots, decoded.output);
  EXPECT_EQ(decoded.output,
            "512,384,3 40,700,1 - -\n"
            "513,385,3 - - -\n"
            "0,0,0 1023,767,15 1,766,7 600,10,2\n"
            "- - - -\n"
            "1023,767,? 300,700,? - 1,2,?\n");
}

}  // namespace
}  // namespace mallet::input::wiimote
