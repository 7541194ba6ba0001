// config/instruments.toml: the shipped presets load, and a malformed file names the file,
// the line and the dotted key.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/config/instruments_config.hpp"
#include "core/file_error.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::file_error_of;

bool mentions(const FileError& e, const std::string& text) {
  return std::string(e.what()).find(text) != std::string::npos;
}

// Line 1 is empty (the raw string starts with a newline); the modes are on lines 6–7.
const char* kGood = R"(
[instrument.bar]
loudness = 0.3
reference_speed_m_per_s = 2.0
brightness = 1.0
modes = [ { ratio = 1.0, gain = 1.0, decay_per_s = 8.0 },
          { ratio = 3.0, gain = 0.4, decay_per_s = 30.0 } ]
)";

std::string with(const std::string& from, const std::string& to) {
  std::string text = kGood;
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(InstrumentsConfig, ShippedFileHasTheFourPresetsTheWallsKnockAndTheStudysClick) {
  const std::vector<ModalPreset> presets = config::load_instruments(test::config_dir() / "instruments.toml");
  ASSERT_EQ(presets.size(), 6u);
  EXPECT_EQ(presets[0].name, "xylophone");
  EXPECT_EQ(presets[1].name, "glockenspiel");
  EXPECT_EQ(presets[2].name, "marimba");
  EXPECT_EQ(presets[3].name, "vibraphone");
  EXPECT_EQ(presets[4].name, "wall");
  // The study's answer bars: a click, every partial 60 dB down within 16 ms (6.9 / decay).
  EXPECT_EQ(presets[5].name, "click");
  for (const Mode& m : presets[5].modes) EXPECT_LT(6.9 / m.decay_per_s, 0.016);
  for (const ModalPreset& p : presets) {
    ASSERT_FALSE(p.modes.empty()) << p.name;
    EXPECT_EQ(p.modes[0].ratio, 1.0) << p.name;
    EXPECT_GT(p.loudness, 0.0) << p.name;
    EXPECT_LE(p.loudness, 1.0) << p.name;
    for (std::size_t k = 1; k < p.modes.size(); ++k) {
      EXPECT_GT(p.modes[k].ratio, p.modes[k - 1].ratio) << p.name;
      EXPECT_GT(p.modes[k].decay_per_s, p.modes[k - 1].decay_per_s) << p.name << ": higher modes decay faster";
    }
  }
  // The bars' physics: a tuned twelfth, a uniform free-free bar, the 1 : 4 : 10 tuning.
  ASSERT_GE(presets[0].modes.size(), 2u);
  EXPECT_EQ(presets[0].modes[1].ratio, 3.0);
  ASSERT_EQ(presets[1].modes.size(), 4u);
  EXPECT_NEAR(presets[1].modes[1].ratio, 2.756, 1e-3);
  EXPECT_NEAR(presets[1].modes[2].ratio, 5.404, 1e-3);
  EXPECT_NEAR(presets[1].modes[3].ratio, 8.933, 1e-3);
  for (int i : {2, 3}) {
    ASSERT_EQ(presets[static_cast<std::size_t>(i)].modes.size(), 3u);
    EXPECT_EQ(presets[static_cast<std::size_t>(i)].modes[1].ratio, 4.0);
    EXPECT_EQ(presets[static_cast<std::size_t>(i)].modes[2].ratio, 10.0);
  }
  // Ring times (60 dB) of the fundamentals, as the file's comments document them.
  EXPECT_NEAR(6.9 / presets[0].modes[0].decay_per_s, 0.45, 0.15);  // xylophone ~0.3–0.6 s
  EXPECT_NEAR(6.9 / presets[1].modes[0].decay_per_s, 3.0, 1.0);    // glockenspiel ~2–4 s
  EXPECT_LT(presets[3].modes[0].decay_per_s, presets[2].modes[0].decay_per_s);  // vibraphone rings longer
}

TEST(InstrumentsConfig, GoodTextParses) {
  const std::vector<ModalPreset> p = config::parse_instruments(kGood, "i.toml");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].name, "bar");
  EXPECT_EQ(p[0].loudness, 0.3);
  EXPECT_EQ(p[0].reference_speed_m_per_s, 2.0);
  ASSERT_EQ(p[0].modes.size(), 2u);
  EXPECT_EQ(p[0].modes[1].ratio, 3.0);
  EXPECT_EQ(p[0].modes[1].gain, 0.4);
  EXPECT_EQ(p[0].modes[1].decay_per_s, 30.0);
}

TEST(InstrumentsConfig, BadRatioNamesFileLineAndKey) {
  const FileError e = file_error_of([] { config::parse_instruments(with("ratio = 3.0", "ratio = -3.0"), "i.toml"); });
  EXPECT_EQ(e.file(), "i.toml");
  EXPECT_EQ(e.line(), 7u);
  EXPECT_EQ(std::string(e.what()).rfind("i.toml:7:", 0), 0u) << e.what();
  EXPECT_TRUE(mentions(e, "instrument.bar.modes[1].ratio: must be > 0")) << e.what();
  EXPECT_TRUE(mentions(e, "-3")) << e.what();

  const FileError first = file_error_of([] { config::parse_instruments(with("ratio = 1.0", "ratio = 1.5"), "i.toml"); });
  EXPECT_EQ(first.line(), 6u);
  EXPECT_TRUE(mentions(first, "instrument.bar.modes[0].ratio")) << first.what();
  EXPECT_TRUE(mentions(first, "must be 1")) << first.what();

  const FileError text = file_error_of([] { config::parse_instruments(with("ratio = 3.0", "ratio = \"3\""), "i.toml"); });
  EXPECT_EQ(text.line(), 7u);
  EXPECT_TRUE(mentions(text, "expected a number")) << text.what();
}

TEST(InstrumentsConfig, TooManyOrNoModesAreRefused) {
  std::string nine = "modes = [\n";
  for (int i = 0; i < 9; ++i) nine += "  { ratio = " + std::to_string(i + 1) + ", gain = 1, decay_per_s = 5 },\n";
  nine += "]";
  const std::string text = with(
      "modes = [ { ratio = 1.0, gain = 1.0, decay_per_s = 8.0 },\n          { ratio = 3.0, gain = 0.4, decay_per_s = 30.0 } ]",
      nine);
  const FileError many = file_error_of([&] { config::parse_instruments(text, "i.toml"); });
  EXPECT_EQ(many.line(), 6u);
  EXPECT_TRUE(mentions(many, "instrument.bar.modes: at most 8 modes, got 9")) << many.what();

  const FileError none = file_error_of([] {
    config::parse_instruments(with("modes = [ { ratio = 1.0, gain = 1.0, decay_per_s = 8.0 },\n          { ratio = 3.0, gain = 0.4, decay_per_s = 30.0 } ]",
                                   "modes = []"),
                              "i.toml");
  });
  EXPECT_EQ(none.line(), 6u);
  EXPECT_TRUE(mentions(none, "instrument.bar.modes")) << none.what();
}

TEST(InstrumentsConfig, UnknownKeysAreRefusedWithTheirLine) {
  const FileError in_mode = file_error_of([] { config::parse_instruments(with("decay_per_s = 30.0", "decay_per_sec = 30.0"), "i.toml"); });
  EXPECT_EQ(in_mode.line(), 7u);
  EXPECT_TRUE(mentions(in_mode, "instrument.bar.modes[1].decay_per_s: missing")) << in_mode.what();

  const FileError extra = file_error_of([] {
    config::parse_instruments(with("decay_per_s = 30.0", "decay_per_s = 30.0, q = 2"), "i.toml");
  });
  EXPECT_EQ(extra.line(), 7u);
  EXPECT_TRUE(mentions(extra, "instrument.bar.modes[1].q: unknown key")) << extra.what();

  const FileError top = file_error_of([] { config::parse_instruments(with("brightness = 1.0", "brightness = 1.0\nloudnes = 0.2"), "i.toml"); });
  EXPECT_EQ(top.line(), 6u);
  EXPECT_TRUE(mentions(top, "instrument.bar.loudnes: unknown key")) << top.what();
}

TEST(InstrumentsConfig, OutOfRangeValuesNameTheKey) {
  struct Case {
    std::string from, to, key;
    unsigned line;
  } cases[] = {
      {"loudness = 0.3", "loudness = 1.5", "instrument.bar.loudness: must be in [0, 1]", 3},
      {"reference_speed_m_per_s = 2.0", "reference_speed_m_per_s = 0", "instrument.bar.reference_speed_m_per_s: must be > 0", 4},
      {"brightness = 1.0", "brightness = -1", "instrument.bar.brightness: must be in [0, 1]", 5},
      {"brightness = 1.0", "brightness = 1.5", "instrument.bar.brightness: must be in [0, 1]", 5},
      {"gain = 0.4", "gain = -0.4", "instrument.bar.modes[1].gain: must be >= 0", 7},
      {"decay_per_s = 8.0", "decay_per_s = -8.0", "instrument.bar.modes[0].decay_per_s: must be >= 0", 6},
  };
  for (const Case& c : cases) {
    const FileError e = file_error_of([&] { config::parse_instruments(with(c.from, c.to), "i.toml"); });
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_TRUE(mentions(e, c.key)) << e.what();
  }
}

TEST(InstrumentsConfig, SyntaxErrorsAndMissingFilesAreLocated) {
  const FileError syntax = file_error_of([] { config::parse_instruments(with("gain = 0.4", "gain = "), "i.toml"); });
  EXPECT_EQ(syntax.line(), 7u);
  EXPECT_GT(syntax.column(), 0u);

  const FileError empty = file_error_of([] { config::parse_instruments("[instrument]\n", "i.toml"); });
  EXPECT_TRUE(mentions(empty, "defines no instrument")) << empty.what();

  const FileError missing = file_error_of([] { config::load_instruments(test::scratch_dir() / "nope.toml"); });
  EXPECT_EQ(missing.line(), 0u);
  EXPECT_TRUE(mentions(missing, "file not found")) << missing.what();
}

}  // namespace
}  // namespace mallet
