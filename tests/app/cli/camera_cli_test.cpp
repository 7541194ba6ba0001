// `mallet camera list` and `mallet camera monitor` as the operator runs them (this machine
// has no camera: what they say without one), and the monitor's loop over a scripted camera
// playing a kept stream.
#include <atomic>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/kiosk/camera_monitor.hpp"
#include "input/camera/frame_stream.hpp"
#include "input/camera/scripted_grabber.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;
namespace cam = mallet::input::camera;

TEST(CameraCli, ListSaysNoneFoundAndExitsZero) {
  const fs::path dir = test::scratch_dir();
  test::write_text(dir / "video0", "a regular file is no camera");
  const test::CliResult r = test::run_mallet("camera list --dir " + dir.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("No camera found among " + dir.string() + "/video*."), std::string::npos) << r.output;
}

TEST(CameraCli, MonitorOfNoCameraSaysWhyAndExitsOne) {
  const fs::path dir = test::scratch_dir();
  const test::CliResult none = test::run_mallet("camera monitor --seconds 0.25 --dir " + dir.string());
  EXPECT_EQ(none.status, 1) << none.output;
  EXPECT_NE(none.output.find("searching  (no camera among " + dir.string() + "/video*)"), std::string::npos)
      << none.output;
  EXPECT_NE(none.output.find("summary: no camera was opened: no camera among " + dir.string() + "/video*"),
            std::string::npos)
      << none.output;
  const test::CliResult null = test::run_mallet("camera monitor --seconds 0.25 --device /dev/null");
  EXPECT_EQ(null.status, 1) << null.output;
  EXPECT_NE(null.output.find("/dev/null: not a V4L2 device"), std::string::npos) << null.output;
  // A name that no camera has: said as such.
  const test::CliResult named = test::run_mallet("camera monitor --seconds 0.1 --device Lumix --dir " + dir.string());
  EXPECT_NE(named.output.find("no camera named like \"Lumix\""), std::string::npos) << named.output;
}

TEST(CameraCli, TheSettingsCameraIsRefusedWithItsLine) {
  const fs::path dir = test::scratch_dir();
  test::write_text(dir / "m.toml", "[camera]\nrate_hz = 240\nexposure_us = 9000\n");
  const test::CliResult r = test::run_mallet("camera monitor --seconds 0.1 --config " + (dir / "m.toml").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find((dir / "m.toml").string() + ":3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("longer than one frame"), std::string::npos) << r.output;
}

TEST(CameraCli, HelpNamesBothCommands) {
  const test::CliResult top = test::run_mallet("--help");
  EXPECT_NE(top.output.find("camera"), std::string::npos) << top.output;
  const test::CliResult r = test::run_mallet("camera monitor --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("--device"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the centroid's noise when the LED is held still"), std::string::npos) << r.output;
}

TEST(CameraMonitor, AStillLedsSpreadIsItsNoiseInTheSummary) {
  std::vector<cam::test::StreamFrame> frames =
      cam::test::read_frame_stream(test::source_dir() / "tests" / "input" / "camera" / "still_led.stream");
  ASSERT_GT(frames.size(), 10u);
  const std::size_t n = frames.size();
  input::SteadyClock clock;
  cam::CameraDevice device(std::make_unique<cam::test::ScriptedGrabber>(cam::test::ScriptedGrabber::Script{frames}),
                           clock);
  char* text = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&text, &size);
  std::atomic<bool> interrupted{false};
  CameraMonitorOptions options;
  options.seconds = 0.3;
  EXPECT_EQ(run_camera_monitor(device, clock, options, interrupted, out), 0);
  std::fclose(out);
  const std::string said(text, size);
  std::free(text);
  EXPECT_NE(said.find("tracking regained at"), std::string::npos) << said;
  EXPECT_NE(said.find("streaming"), std::string::npos) << said;
  EXPECT_NE(said.find("summary: camera /dev/video7 (Scripted Camera, test) 160x120 grey at 240 Hz"), std::string::npos)
      << said;
  EXPECT_NE(said.find("  frames " + std::to_string(n) + ", dropped by the driver 0, unreadable 0"), std::string::npos)
      << said;
  EXPECT_NE(said.find("  LED in " + std::to_string(n) + " of " + std::to_string(n) + " frames"), std::string::npos)
      << said;
  // The spread of the centroid over the still stream, recomputed here from the truth-free
  // samples: what the summary prints is that figure, small against a pixel.
  LedSpread spread;
  cam::CameraTracker tracker;
  for (const cam::test::StreamFrame& f : frames)
    if (const auto s = tracker.on_frame(f.frame()); s && s->has_point) spread.add(s->point.x, s->point.y);
  char expect[96];
  std::snprintf(expect, sizeof expect, "its spread x %.3f px, y %.3f px RMS", spread.rms_x(), spread.rms_y());
  EXPECT_NE(said.find(expect), std::string::npos) << said;
  EXPECT_LT(spread.rms_x(), 0.1);
  EXPECT_GT(spread.rms_x(), 0.0);
}

TEST(CameraMonitor, LedSpreadIsTheSampleStandardDeviation) {
  LedSpread s;
  EXPECT_EQ(s.rms_x(), 0.0);
  for (double x : {1.0, 2.0, 3.0, 4.0}) s.add(x, 10.0);
  EXPECT_NEAR(s.rms_x(), 1.2909944487, 1e-9);  // sqrt(5/3)
  EXPECT_EQ(s.rms_y(), 0.0);
}

}  // namespace
}  // namespace mallet::app
