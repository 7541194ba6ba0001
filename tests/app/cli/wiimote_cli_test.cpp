// `mallet wiimote list` and `mallet wiimote monitor`, run as the operator runs them (no
// remote is needed: monitor --replay plays a recording; list and a live monitor are
// checked for what they say when no remote is there).
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "run_cli.hpp"
#include "app/kiosk/wiimote_monitor.hpp"
#include "input/wiimote/reports.hpp"
#include "test_paths.hpp"
#include "input/wiimote/wiimote_test_support.hpp"

namespace mallet::app {
namespace {

namespace wm = mallet::input::wiimote;
using wm::test::kMs;

constexpr Nanos kT0 = 77 * kNanosPerSecond;

//! 1.5 s of a still LED at 100 Hz, a status report, 0.4 s without the LED, then it is back.
std::string recording() {
  std::ostringstream out;
  wm::ReplayWriter writer(out);
  Nanos t = kT0;
  for (int i = 0; i < 150; ++i, t += 10 * kMs) writer.write(t, wm::test::ir_report({{512, 384, 3}}));
  writer.write(t, wm::test::status_report(0xc8));
  for (int i = 0; i < 40; ++i, t += 10 * kMs) writer.write(t, wm::test::ir_report({}));
  for (int i = 0; i < 10; ++i, t += 10 * kMs) writer.write(t, wm::test::ir_report({{700, 100, 2}}));
  return out.str();
}

bool remote_present() { return test::run_mallet("wiimote list").output.find("No Wii Remote found") == std::string::npos; }

TEST(WiimoteMonitorCli, ReplayPrintsStateLinesAndTrackingEvents) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "s.replay") << recording();
  const test::CliResult r = test::run_mallet("wiimote monitor --replay " + (dir / "s.replay").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("   0.000 s  tracking regained at 512,384\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("   0.100 s  replay       0.0 Hz  battery ?  tracking  led 512,384  dots 512,384,3 - - -\n"),
            std::string::npos)
      << r.output;
  // After a full second the rate is known, and after the status report the battery.
  EXPECT_NE(r.output.find("   1.100 s  replay     100.0 Hz  battery ?  tracking  led 512,384"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("   1.600 s  replay     100.0 Hz  battery 0xc8  tracking"), std::string::npos) << r.output;
  // lost_after_ms = 150 after the last dot at 1.490 s.
  EXPECT_NE(r.output.find("   1.640 s  tracking lost\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  lost      led 512,384  dots - - - -\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("   1.900 s  tracking regained at 700,100\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("replayed 201 of 201 report(s): 201 reports (200 IR, 1 status, 0 malformed)"),
            std::string::npos)
      << r.output;
}

TEST(WiimoteMonitorCli, ReplayStopsAfterSeconds) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "s.replay") << recording();
  const test::CliResult r = test::run_mallet("wiimote monitor --seconds 0.5 --replay " + (dir / "s.replay").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("replayed 50 of 201 report(s)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("   0.600 s"), std::string::npos) << r.output;
}

TEST(WiimoteMonitorCli, BadRecordingAndBadFlagsExit2) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "bad.replay") << "# mallet-wiimote-replay 1\n10 33 00\nten 33\n";
  const test::CliResult bad = test::run_mallet("wiimote monitor --replay " + (dir / "bad.replay").string());
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find((dir / "bad.replay").string() + ":3:"), std::string::npos) << bad.output;

  const test::CliResult both =
      test::run_mallet("wiimote monitor --replay x.replay --record y.replay");
  EXPECT_EQ(both.status, 2) << both.output;
  EXPECT_NE(both.output.find("excludes"), std::string::npos) << both.output;

  std::ofstream(dir / "bad.toml") << "[wiimote]\nsensitivity = \"loud\"\n";
  const test::CliResult config =
      test::run_mallet("wiimote monitor --seconds 0.1 --config " + (dir / "bad.toml").string());
  EXPECT_EQ(config.status, 2) << config.output;
  EXPECT_NE(config.output.find("wiimote.sensitivity: unknown preset \"loud\""), std::string::npos) << config.output;
}

TEST(WiimoteListCli, SaysWhatItSeesAndExits0) {
  const test::CliResult r = test::run_mallet("wiimote list");
  EXPECT_EQ(r.status, 0) << r.output;
  if (r.output.find("No Wii Remote found") != std::string::npos) {
    EXPECT_NE(r.output.find(std::string(wm::kUdevRulePath)), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(std::string(wm::kUdevRule)), std::string::npos) << r.output;
  } else {
    EXPECT_NE(r.output.find("path"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("RVL-CNT-01"), std::string::npos) << r.output;
  }
}

TEST(WiimoteMonitorCli, WithoutARemoteItKeepsSearchingThenExits1) {
  if (remote_present()) GTEST_SKIP() << "a Wii Remote is connected to this machine";
  const auto dir = test::scratch_dir();
  const test::CliResult r =
      test::run_mallet("wiimote monitor --seconds 0.35 --record " + (dir / "rec.replay").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("searching  retry in"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no Wii Remote found"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mallet: no Wii Remote was connected"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("recorded 0 report(s)"), std::string::npos) << r.output;
  // The recording exists and is a valid (empty) replay file.
  EXPECT_TRUE(wm::read_replay(dir / "rec.replay").reports.empty());
}

TEST(WiimoteCli, HelpNamesTheSubcommandsAndTheContract) {
  const test::CliResult help = test::run_mallet("wiimote --help");
  EXPECT_EQ(help.status, 0);
  for (const char* word : {"list", "monitor", "decode"}) EXPECT_NE(help.output.find(word), std::string::npos) << word;
  const test::CliResult monitor = test::run_mallet("wiimote monitor --help");
  for (const char* word : {"--seconds", "--record", "--replay", "--device", "Ctrl+C", "Exit 0 if a remote"})
    EXPECT_NE(monitor.output.find(word), std::string::npos) << word;
  const test::CliResult list = test::run_mallet("wiimote list --help");
  EXPECT_NE(list.output.find("still exits 0"), std::string::npos) << list.output;
}

TEST(WiimoteList, FormatsDevicesOrTheHints) {
  const std::string none = format_device_list({});
  EXPECT_EQ(none.rfind("No Wii Remote found", 0), 0u) << none;
  EXPECT_NE(none.find("/usr/lib/udev/rules.d/70-mallet-wiimote.rules"), std::string::npos) << none;
  EXPECT_NE(none.find("/etc/udev/rules.d/70-mallet-wiimote.rules"), std::string::npos) << none;
  EXPECT_NE(none.find(R"(KERNELS=="*:057E:0306.*|*:057E:0330.*", TAG+="uaccess")"), std::string::npos) << none;

  const std::string two = format_device_list({
      {"/dev/hidraw3", wm::kNintendoVendorId, wm::kWiiRemoteProductId, "00:1f:32:aa:bb:cc", "Nintendo RVL-CNT-01"},
      {"/dev/hidraw7", wm::kNintendoVendorId, wm::kWiiRemoteTrProductId, "", "Nintendo RVL-CNT-01-TR"},
  });
  std::istringstream lines(two);
  std::string header, first, second, footer;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  std::getline(lines, footer);
  EXPECT_EQ(header.rfind("path", 0), 0u) << two;
  EXPECT_EQ(first.rfind("/dev/hidraw3", 0), 0u) << two;
  EXPECT_NE(first.find("RVL-CNT-01 (0306)"), std::string::npos) << two;
  EXPECT_NE(first.find("00:1f:32:aa:bb:cc"), std::string::npos) << two;
  EXPECT_NE(second.find("RVL-CNT-01-TR (0330)"), std::string::npos) << two;
  EXPECT_NE(second.find(" - "), std::string::npos) << "no serial shown as -: " << two;
  EXPECT_EQ(footer.rfind("2 Wii Remote(s)", 0), 0u) << two;
}

TEST(WiimoteMonitor, LineFormat) {
  MonitorLine line;
  line.t_rel_ns = 1'234'500'000;
  line.link = "running";
  line.remote.ir_rate_hz = 99.96;
  line.remote.battery = 0x3a;
  line.remote.battery_low = true;
  line.remote.last_slots = {IrDot{10, 20, 4}, std::nullopt, IrDot{30, 40, -1}, std::nullopt};
  line.tracking = true;
  line.point = IrPoint{0, 10.4, 19.6, 4, 0};
  EXPECT_EQ(format_monitor_line(line),
            "   1.234 s  running    100.0 Hz  battery 0x3a LOW  tracking  led 10,20  dots 10,20,4 - 30,40,? -");
  line.link = "searching";
  line.note = "retry in 0.5 s: no Wii Remote found";
  EXPECT_EQ(format_monitor_line(line), "   1.234 s  searching  retry in 0.5 s: no Wii Remote found");
  EXPECT_EQ(format_event_line(2'000'000'000, IrTrackerEvent::jumped, IrPoint{0, 1, 2, 3, 0}),
            "   2.000 s  tracking jumped at 1,2");
  EXPECT_EQ(format_event_line(2'000'000'000, IrTrackerEvent::lost, IrPoint{0, 1, 2, 3, 0}), "   2.000 s  tracking lost");
}

}  // namespace
}  // namespace mallet::app
