// `mallet doctor`'s judgements: the thresholds, the line format and the exit status.
#include <gtest/gtest.h>

#include "core/doctor_check.hpp"

namespace mallet {
namespace {

constexpr std::uint64_t kMiB = 1024 * 1024;

TEST(DoctorCheck, OneLineWithLevelNameFoundAndFix) {
  const std::string line = format_check({"audio", CheckLevel::fail, "no output device", "connect the sound card"});
  EXPECT_EQ(line, "fail  audio        no output device -> fix: connect the sound card");
  EXPECT_EQ(format_check({"disk", CheckLevel::ok, "5.0 GiB free", ""}).find("fix"), std::string::npos);
}

TEST(DoctorCheck, ExitStatusIsOneOnlyWhenSomethingFails) {
  EXPECT_EQ(doctor_exit_status({{"a", CheckLevel::ok, "", ""}, {"b", CheckLevel::warn, "", ""}}), 0);
  EXPECT_EQ(doctor_exit_status({{"a", CheckLevel::ok, "", ""}, {"b", CheckLevel::fail, "", ""}}), 1);
}

TEST(DoctorCheck, FreeSpaceThresholds) {
  EXPECT_EQ(judge_free_space("/var", 50 * kMiB).level, CheckLevel::fail);
  EXPECT_EQ(judge_free_space("/var", 500 * kMiB).level, CheckLevel::warn);
  const DoctorCheck ok = judge_free_space("/var", 5 * 1024 * kMiB);
  EXPECT_EQ(ok.level, CheckLevel::ok);
  EXPECT_NE(ok.found.find("5.0 GiB free in /var"), std::string::npos) << ok.found;
}

TEST(DoctorCheck, SoftwareRendererOnALargeDisplayWarnsWithItsFrameTime) {
  const DoctorCheck big = judge_renderer("llvmpipe", true, 1920, 1080, 2.4);
  EXPECT_EQ(big.level, CheckLevel::warn);
  EXPECT_NE(big.found.find("1920x1080 frame takes 2.4 ms"), std::string::npos) << big.found;
  EXPECT_EQ(judge_renderer("llvmpipe", true, 1280, 720, 1.2).level, CheckLevel::ok);
  EXPECT_EQ(judge_renderer("Intel UHD", false, 3840, 2160, 3.0).level, CheckLevel::ok);
  EXPECT_EQ(judge_renderer("llvmpipe", true, 3840, 2160, 20.0).level, CheckLevel::fail);
}

TEST(DoctorCheck, ParsesTheCalibrationsUtcStamp) {
  EXPECT_EQ(parse_utc("1970-01-02T00:00:00Z"), 86400);
  EXPECT_EQ(parse_utc("2025-05-01T09:30:00Z"), 1746091800);
  EXPECT_FALSE(parse_utc("yesterday"));
  EXPECT_FALSE(parse_utc("2025-13-01T09:30:00Z"));
}

TEST(DoctorCheck, Calibration) {
  const std::int64_t now = *parse_utc("2026-01-31T00:00:00Z");
  EXPECT_EQ(judge_calibration("c.toml", std::nullopt, "", now, std::nullopt).level, CheckLevel::warn);
  EXPECT_EQ(judge_calibration("c.toml", std::nullopt, "c.toml:3: bad", now, std::nullopt).found, "c.toml:3: bad");
  Calibration c;
  c.created_utc = "2026-01-01T00:00:00Z";
  c.max_error_screen_px = 4.0;
  c.remote = "00:19:1d:aa:bb:cc";
  const DoctorCheck fresh = judge_calibration("c.toml", c, "", now, c.remote);
  EXPECT_EQ(fresh.level, CheckLevel::ok) << fresh.found;
  EXPECT_NE(fresh.found.find("30 days ago"), std::string::npos) << fresh.found;
  EXPECT_NE(fresh.found.find("max error 4.0 px"), std::string::npos) << fresh.found;
  EXPECT_EQ(judge_calibration("c.toml", c, "", now, std::string("00:19:1d:00:00:01")).level, CheckLevel::warn);
  Calibration rough = c;
  rough.max_error_screen_px = 40;
  EXPECT_EQ(judge_calibration("c.toml", rough, "", now, std::nullopt).level, CheckLevel::warn);
  Calibration old = c;
  old.created_utc = "2025-06-01T00:00:00Z";
  EXPECT_EQ(judge_calibration("c.toml", old, "", now, std::nullopt).level, CheckLevel::warn);
}

}  // namespace
}  // namespace mallet
