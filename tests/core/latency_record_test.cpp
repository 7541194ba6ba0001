// latency.toml (core/latency_record.hpp) and display_latency.toml (core/display_latency_record.hpp): written, read back, a malformed one refused with its
// place named, an absent one none.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/file_error.hpp"
#include "core/display_latency_record.hpp"
#include "core/latency_record.hpp"

namespace mallet {
namespace {

TEST(LatencyRecord, WhatIsWrittenReadsBackAndABadOneIsRefusedWithItsPlace) {
  const auto dir = std::filesystem::temp_directory_path() / ("mallet-latency-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EXPECT_FALSE(load_latency_record(dir / "latency.toml"));
  LatencyMeasurement m;
  m.measured_utc = "2026-12-06T09:30:00Z";
  m.sample_rate_hz = 48000;
  m.round_trip_samples = 496.25;
  m.portaudio_input_latency_ms = 1.5;
  m.portaudio_output_latency_ms = 5.333;
  m.output_device = "USB \"Audio\" card";
  m.input_device = "USB";
  std::ofstream(dir / "latency.toml") << format_latency_record(m);
  const std::optional<LatencyMeasurement> back = load_latency_record(dir / "latency.toml");
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->round_trip_samples, 496.25, 1e-9);
  EXPECT_NEAR(back->output_latency_ms(), 496.25 / 48 - 1.5, 1e-9);
  EXPECT_EQ(back->output_device, m.output_device);
  EXPECT_EQ(back->measured_utc, m.measured_utc);
  std::ofstream(dir / "bad.toml") << "format_version = 1\nmeasured_utc = \"x\"\nsample_rate_hz = 10\n";
  try {
    load_latency_record(dir / "bad.toml");
    ADD_FAILURE() << "accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sample_rate_hz"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(DisplayLatencyRecord, WhatIsWrittenReadsBackAndABadOneIsRefusedWithItsPlace) {
  const auto dir = std::filesystem::temp_directory_path() / ("mallet-display-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EXPECT_FALSE(load_display_latency(dir / "display_latency.toml"));
  DisplayLatencyMeasurement m;
  m.measured_utc = "2026-12-06T09:30:00Z";
  m.display_latency_ms = 23.456;
  m.min_ms = 22.5;
  m.max_ms = 25.25;
  m.squares_seen = 9;
  m.squares = 10;
  m.input_device = "USB \"Audio\"";
  m.photodiode_channel = 2;
  m.saved = true;
  std::ofstream(dir / "display_latency.toml") << format_display_latency(m);
  const std::optional<DisplayLatencyMeasurement> back = load_display_latency(dir / "display_latency.toml");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->display_latency_ms, 23.456);
  EXPECT_EQ(back->max_ms, 25.25);
  EXPECT_EQ(back->squares_seen, 9);
  EXPECT_EQ(back->input_device, m.input_device);
  EXPECT_EQ(back->photodiode_channel, 2);
  EXPECT_TRUE(back->saved);
  std::ofstream(dir / "bad.toml") << "format_version = 1\nmeasured_utc = \"x\"\ndisplay_latency_ms = 500\n";
  try {
    load_display_latency(dir / "bad.toml");
    ADD_FAILURE() << "accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("display_latency_ms"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mallet
