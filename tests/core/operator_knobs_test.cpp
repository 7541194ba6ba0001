// The operator page's arrows move the volume and the gain one step toward their end of the
// settings' range, never the other way (Up at 200 % used to set 100 %); and the page's range
// is the settings file's, end for end.
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/config/app_config_loader.hpp"
#include "core/file_error.hpp"
#include "core/operator_knobs.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

TEST(OperatorKnobs, UpNeverLowersTheVolumeTheSettingsAllow) {
  EXPECT_DOUBLE_EQ(knob_step(2.0, kVolumeKnob, true), 2.05);
  EXPECT_DOUBLE_EQ(knob_step(4.0, kVolumeKnob, true), 4.0);
  EXPECT_DOUBLE_EQ(knob_step(3.98, kVolumeKnob, true), 4.0);
  for (double v = 0.0; v <= 4.0; v += 0.13) EXPECT_GE(knob_step(v, kVolumeKnob, true), v) << v;
}

TEST(OperatorKnobs, DownNeverRaisesAndStopsAtZero) {
  EXPECT_DOUBLE_EQ(knob_step(0.02, kVolumeKnob, false), 0.0);
  EXPECT_DOUBLE_EQ(knob_step(0.0, kVolumeKnob, false), 0.0);
  for (double v = 0.0; v <= 4.0; v += 0.13) EXPECT_LE(knob_step(v, kVolumeKnob, false), v) << v;
}

TEST(OperatorKnobs, TheGainReachesItsSettingsRange) {
  EXPECT_DOUBLE_EQ(knob_step(2.0, kGainKnob, true), 2.02);  // above the old 1.0 cap
  EXPECT_DOUBLE_EQ(knob_step(10.0, kGainKnob, true), 10.0);
  EXPECT_DOUBLE_EQ(knob_step(2.0, kGainKnob, false), 1.98);
}

// Each end of the page's range loads from the file; a step past either end is refused.
void expect_file_range_is(const std::string& section, const std::string& key, const KnobRange& k) {
  const auto text = [&](double v) { return fmt::format("[{}]\n{} = {}\n", section, key, v); };
  EXPECT_NO_THROW(config::parse_app_config(text(k.lo), "c.toml")) << key << " " << k.lo;
  EXPECT_NO_THROW(config::parse_app_config(text(k.hi), "c.toml")) << key << " " << k.hi;
  const FileError above = test::file_error_of([&] { config::parse_app_config(text(k.hi + k.step), "c.toml"); });
  EXPECT_NE(std::string(above.what()).find(fmt::format("must be in [{}, {}]", k.lo, k.hi)), std::string::npos)
      << above.what();
  EXPECT_THROW(config::parse_app_config(text(k.lo - k.step), "c.toml"), FileError) << key;
}

TEST(OperatorKnobs, ThePagesRangeIsTheSettingsFilesRange) {
  expect_file_range_is("audio", "volume", kVolumeKnob);
  expect_file_range_is("actuator", "gain", kGainKnob);
  EXPECT_EQ(config::parse_app_config("[audio]\nvolume = 4\n", "c.toml").audio.volume, kVolumeKnob.hi);
  EXPECT_EQ(config::parse_app_config("[actuator]\ngain = 10\n", "c.toml").actuator.gain, kGainKnob.hi);
}

}  // namespace
}  // namespace mallet
