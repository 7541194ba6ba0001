// Which actuator calibration the engine applies (audio/audio_setup.hpp): the state folder's
// file when [actuator] equalize allows and it was measured at the audio's rate; none
// otherwise, a file that does not read included (the kiosk plays on uncorrected).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "audio/audio_setup.hpp"

namespace mallet::audio {
namespace {

ActuatorEq sample_eq() {
  ActuatorEq e;
  e.created_utc = "2026-12-06T09:30:00Z";
  e.sample_rate_hz = 48000;
  e.band_low_hz = 60;
  e.band_high_hz = 500;
  e.gain_limit_db = 12;
  e.taps = std::vector<double>(32, 0.01);
  e.taps[0] = 1.0;
  return e;
}

TEST(ActuatorEqInForce, TheFileWhenEqualizeAllowsAndItsRateIsTheAudiosElseNone) {
  const auto dir = std::filesystem::temp_directory_path() / ("mallet-eq-force-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / "actuator_eq.toml";
  AppConfig config;
  EXPECT_FALSE(actuator_eq_in_force(config, 48000, path)) << "no file";
  write_actuator_eq_file(path, sample_eq());
  const std::optional<ActuatorEq> in_force = actuator_eq_in_force(config, 48000, path);
  ASSERT_TRUE(in_force);
  EXPECT_EQ(in_force->hash(), sample_eq().hash());
  EXPECT_FALSE(actuator_eq_in_force(config, 44100, path)) << "measured at another rate";
  config.actuator.equalize = false;
  EXPECT_FALSE(actuator_eq_in_force(config, 48000, path)) << "equalize = false";
  config.actuator.equalize = true;
  std::ofstream(path) << "format_version = 1\ntaps = [\n";
  EXPECT_FALSE(actuator_eq_in_force(config, 48000, path)) << "a file that does not read";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mallet::audio
