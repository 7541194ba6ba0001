// `mallet calibrate actuator` and `mallet calibrate latency` refuse what they cannot measure
// with, before any device is opened, with one line and exit status 2 (the contract in their
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
  EXPECT_EQ(lines_of(r.output), 1) << r.output;
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
  EXPECT_NE(l.output.find("--loopback"), std::string::npos);
  EXPECT_NE(l.output.find("audio_output_latency_ms"), std::string::npos);
}

}  // namespace
}  // namespace mallet::app
