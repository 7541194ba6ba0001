// actuator_eq.toml (core/actuator_eq_file.hpp): written, read back exactly, its identity,
// and every malformed file refused with its place named.
#include <gtest/gtest.h>

#include <cmath>
#include <unistd.h>

#include <filesystem>

#include "core/actuator_eq_file.hpp"
#include "core/file_error.hpp"

namespace mallet {
namespace {

ActuatorEq sample() {
  ActuatorEq e;
  e.created_utc = "2026-12-06T09:30:00Z";
  e.created_by = "mallet calibrate actuator";
  e.sensor = "piezo disc \"A\", stick tip";
  e.sample_rate_hz = 48000;
  e.sweep_low_hz = 20;
  e.sweep_high_hz = 2000;
  e.level_db = -20;
  e.resonance_hz = 179.59392772949997;
  e.resonance_db = 5.9;
  e.band_low_hz = 63.5;
  e.band_high_hz = 1522.2;
  e.delay_ms = 0.77;
  e.gain_limit_db = 12;
  e.target_db = -6.8;
  e.latency_samples = -66.1;
  e.frequency_hz = {20, 21.2, 22.4};
  e.magnitude_db = {-30, -29, -28.1};
  e.phase_deg = {170, 168, 166.5};
  for (int i = 0; i < 32; ++i) e.taps.push_back(std::sin(i * 0.37) / (1 + i) + 1e-17 * i);
  return e;
}

TEST(ActuatorEqFile, WhatIsWrittenReadsBackAsTheSameNumbersAndIdentity) {
  const ActuatorEq e = sample();
  const ActuatorEq back = parse_actuator_eq(format_actuator_eq(e), "actuator_eq.toml");
  EXPECT_EQ(back.taps, e.taps);
  EXPECT_EQ(back.sensor, e.sensor);
  EXPECT_EQ(back.resonance_hz, e.resonance_hz);
  EXPECT_EQ(back.band_low_hz, e.band_low_hz);
  EXPECT_EQ(back.band_high_hz, e.band_high_hz);
  EXPECT_EQ(back.phase_deg, e.phase_deg);
  EXPECT_EQ(back.hash(), e.hash());
  EXPECT_EQ(back.hash().size(), 16u);
  ActuatorEq other = e;
  other.taps[5] = std::nextafter(other.taps[5], 1.0);
  EXPECT_NE(other.hash(), e.hash());
  EXPECT_EQ(e.alignment_samples(), 0);
  other.latency_samples = 2.6;
  EXPECT_EQ(other.alignment_samples(), 3);
}

TEST(ActuatorEqFile, AMalformedFileIsRefusedNamingTheFileThePlaceAndTheProblem) {
  const std::string good = format_actuator_eq(sample());
  const auto refused = [&](std::string text, const std::string& expected) {
    try {
      parse_actuator_eq(text, "state/actuator_eq.toml");
      ADD_FAILURE() << "accepted; expected " << expected;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find("state/actuator_eq.toml:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return t.replace(at, from.size(), to);
  };
  refused(replaced("format_version = 1", "format_version = 2"), "format_version");
  refused(replaced("sample_rate_hz = 48000", "sample_rate_hz = 48000\nsamplerate = 1"), "samplerate");
  refused(replaced("gain_limit_db = 12", "gain_limit_db = 90"), "gain_limit_db");
  refused(replaced("taps = [", "taps = [nan, "), "taps");
  refused(replaced("usable_band_hz = [63.5, ", "usable_band_hz = [63.5, 1, "), "usable_band_hz");
  refused(replaced("[inverse]", "[inverse_]"), "inverse");
  refused(good.substr(0, good.size() / 2), "actuator_eq.toml:");
}

TEST(ActuatorEqFile, WritingRefusesWhatWouldNotLoadAndLeavesNoFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("mallet-eq-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  ActuatorEq e = sample();
  e.taps.resize(4);
  EXPECT_THROW(write_actuator_eq_file(dir / "actuator_eq.toml", e), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "actuator_eq.toml"));
  write_actuator_eq_file(dir / "actuator_eq.toml", sample());
  EXPECT_EQ(load_actuator_eq(dir / "actuator_eq.toml").taps, sample().taps);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mallet
