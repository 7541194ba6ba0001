// The quality preset in config: it sets defaults, a knob written in the file wins, and a
// bad name is refused with its line.
#include <gtest/gtest.h>

#include "core/config/app_config_loader.hpp"
#include "core/file_error.hpp"
#include "core/quality.hpp"

namespace mallet {
namespace {

TEST(QualityConfig, BalancedIsTheBuiltInDefaults) {
  AppConfig c;
  apply_quality(Quality::balanced, c);
  const AppConfig d;
  EXPECT_EQ(c.render.msaa, d.render.msaa);
  EXPECT_EQ(c.render.shadow, d.render.shadow);
  EXPECT_EQ(c.render.present_mode, d.render.present_mode);
  EXPECT_EQ(c.audio.frames_per_buffer, d.audio.frames_per_buffer);
  EXPECT_EQ(c.audio.schedule_ahead_ms, d.audio.schedule_ahead_ms);
  EXPECT_EQ(c.audio.max_modes, d.audio.max_modes);
  EXPECT_EQ(c.pointer.beta_per_m, d.pointer.beta_per_m);
}

TEST(QualityConfig, APresetSetsItsKnobs) {
  const AppConfig fast = config::parse_app_config("quality = \"fast\"\n", "c.toml");
  EXPECT_EQ(fast.quality, Quality::fast);
  EXPECT_EQ(fast.render.msaa, "1");
  EXPECT_TRUE(fast.render.shadow);
  EXPECT_EQ(fast.render.present_mode, PresentPacing::fifo);
  const AppConfig exact = config::parse_app_config("quality = \"exact\"\n", "c.toml");
  EXPECT_EQ(exact.render.msaa, "4");
  EXPECT_EQ(exact.audio.schedule_ahead_ms, 12.0);
  EXPECT_EQ(exact.audio.frames_per_buffer, 64);
}

TEST(QualityConfig, AKnobWrittenInTheFileOverridesThePreset) {
  const AppConfig c = config::parse_app_config(
      "quality = \"fast\"\n[audio]\nframes_per_buffer = 32\nmax_modes = 3\n[render]\nshadow = false\n", "c.toml");
  EXPECT_EQ(c.quality, Quality::fast);
  EXPECT_EQ(c.audio.frames_per_buffer, 32);
  EXPECT_EQ(c.audio.max_modes, 3);
  EXPECT_FALSE(c.render.shadow);
  EXPECT_EQ(c.render.msaa, "1");  // not written: the preset's
}

TEST(QualityConfig, BadValuesNameTheirKeyAndLine) {
  try {
    config::parse_app_config("# a comment\nquality = \"fastest\"\n", "c.toml");
    FAIL() << "accepted";
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 2u);
    const std::string what = e.what();
    EXPECT_NE(what.find("quality"), std::string::npos) << what;
    EXPECT_NE(what.find("\"fastest\""), std::string::npos) << what;
  }
  try {
    config::parse_app_config("[audio]\nmax_modes = 9\n", "c.toml");
    FAIL() << "accepted";
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_NE(std::string(e.what()).find("max_modes"), std::string::npos) << e.what();
  }
}

TEST(QualityConfig, NamesRoundTrip) {
  for (Quality q : {Quality::fast, Quality::balanced, Quality::exact}) EXPECT_EQ(parse_quality(to_string(q)), q);
  EXPECT_FALSE(parse_quality("Fast").has_value());
}

}  // namespace
}  // namespace mallet
