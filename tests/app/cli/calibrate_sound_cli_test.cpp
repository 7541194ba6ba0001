// `mallet calibrate actuator` and `mallet calibrate latency` refuse what they cannot measure
// with (no sensor, one channel for two things, a photodiode without a screen), before any
// device is opened, with one line and exit status 2 (the contract in their
// --help). The measurements themselves run through a real PortAudio stream in
// `bench.actuator` (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

int lines_of(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line))
    if (line.rfind("mallet: ", 0) == 0) ++n;
  return n;
}

TEST(CalibrateSoundCli, LatencyWithoutALoopbackSaysWhatToGiveInOneLineAndExitsTwo) {
  const test::CliResult r = test::run_mallet("calibrate latency");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("mallet: nothing to measure with: give --loopback CH"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("or --photodiode CH"), std::string::npos) << r.output;
  EXPECT_EQ(lines_of(r.output), 1) << r.output;
}

TEST(CalibrateSoundCli, APhotodiodeWithoutAScreenOrOnTheLoopbacksChannelIsRefusedInOneLine) {
  const test::CliResult screenless =
      test::run_command("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(MALLET_TEST_BINARY) +
                        " calibrate latency --photodiode 2");
  EXPECT_EQ(screenless.status, 2) << screenless.output;
  EXPECT_NE(screenless.output.find("mallet: --photodiode needs the kiosk's screen"), std::string::npos)
      << screenless.output;
  EXPECT_EQ(lines_of(screenless.output), 1) << screenless.output;
  const test::CliResult same = test::run_mallet("calibrate latency --loopback 2 --photodiode 2");
  EXPECT_EQ(same.status, 2) << same.output;
  EXPECT_NE(same.output.find("both input channel 2"), std::string::npos) << same.output;
}

TEST(CalibrateSoundCli, TheSensorAndTheLoopbackOnOneChannelAreRefused) {
  const test::CliResult r = test::run_mallet("calibrate actuator --channel 2 --loopback 2");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--loopback"), std::string::npos) << r.output;
}

TEST(CalibrateSoundCli, VerifyWithAMalformedCalibrationNamesTheFileAndThePlace) {
  const auto dir = test::scratch_dir();
  const auto eq = dir / "actuator_eq.toml";
  std::ofstream(eq) << "format_version = 1\nsample_rate_hz = 48000\nsweep_hz = [20.0]\n";
  const test::CliResult r = test::run_mallet("calibrate actuator --verify --out " + eq.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(eq.string() + ":3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sweep_hz"), std::string::npos) << r.output;
}

TEST(CalibrateSoundCli, HelpStatesTheContract) {
  const test::CliResult a = test::run_mallet("calibrate actuator --help");
  EXPECT_EQ(a.status, 0);
  for (const char* flag : {"--input", "--channel", "--level", "--verify", "--out", "--loopback"})
    EXPECT_NE(a.output.find(flag), std::string::npos) << flag;
  EXPECT_NE(a.output.find("this sound card has no input"), std::string::npos) << a.output;
  const test::CliResult l = test::run_mallet("calibrate latency --help");
  EXPECT_EQ(l.status, 0);
  for (const char* words : {"--loopback", "--photodiode", "audio_output_latency_ms", "display_latency_ms",
                            "61-measured-display-latency.toml", "Enter", "photodiode_channel"})
    EXPECT_NE(l.output.find(words), std::string::npos) << words;
}

}  // namespace
}  // namespace mallet::app
