// The kiosk's start when its settings are refused (kiosk_setup.hpp: start_setup): it comes
// up on its last good settings, else on the shipped defaults, and says so in one line naming
// the file, the line and the problem; a reload (the same route, load_setup) is refused.
#include <fstream>

#include <gtest/gtest.h>

#include "app/kiosk/kiosk_setup.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

using test::write_text;

struct KioskStart : ::testing::Test {
  fs::path dir = test::scratch_dir();
  fs::path settings = dir / "etc" / "mallet.toml";
  fs::path last_good = dir / "state" / kLastGoodSettings;
  KioskOptions options;
  void SetUp() override {
    options.config = settings;
    options.config_dir = dir / "etc" / "mallet.toml.d";
  }
};

TEST_F(KioskStart, SettingsThatLoadAreItsOwnAndAreWhatItKeeps) {
  write_text(settings, "[audio]\nvolume = 0.5\n");
  const Result<KioskSetup, std::string> s = start_setup(options, last_good);
  ASSERT_TRUE(s) << s.error();
  EXPECT_TRUE(s->refused.empty());
  EXPECT_DOUBLE_EQ(s->config.audio.volume, 0.5);
  const std::string kept = last_good_text(*s);
  EXPECT_NE(kept.find("volume = 0.5  # from " + settings.string() + ":2"), std::string::npos) << kept;
  EXPECT_EQ(kept.rfind("# The kiosk's last good settings", 0), 0u) << kept;
}

TEST_F(KioskStart, BrokenSettingsStartOnTheLastGoodOnesWithTheProblemInOneLine) {
  write_text(settings, "[audio]\nvolume = 0.5\n[metrics]\ntextfile = \"mallet.prom\"\n");
  const Result<KioskSetup, std::string> good = start_setup(options, last_good);
  ASSERT_TRUE(good) << good.error();
  write_text(last_good, last_good_text(*good));  // as the kiosk keeps it

  write_text(settings, "[audio]\nvolume = \"loud\n");  // a missing quote
  ASSERT_FALSE(load_setup(options)) << "a reload is refused: the running settings stay";
  const Result<KioskSetup, std::string> s = start_setup(options, last_good);
  ASSERT_TRUE(s) << s.error();
  EXPECT_DOUBLE_EQ(s->config.audio.volume, 0.5) << "the last good settings";
  EXPECT_EQ(s->config.metrics.textfile, (settings.parent_path() / "mallet.prom").string())
      << "relative paths resolve beside the operator's file, as they did";
  EXPECT_EQ(s->refused.rfind("settings refused: " + settings.string() + ":2:", 0), 0u) << s->refused;
  EXPECT_NE(s->refused.find("; the kiosk runs on its last good settings (" + last_good.string() + ")"),
            std::string::npos)
      << s->refused;
  EXPECT_EQ(s->refused.find('\n'), std::string::npos) << "one line";
  ASSERT_FALSE(s->problems.empty());
  EXPECT_EQ(s->problems.front(), s->refused) << "first on the operator page";
  EXPECT_TRUE(last_good_text(*s).empty()) << "a fallback is not kept as the last good settings";
  EXPECT_EQ(s->scene.file, (test::config_dir() / "scenes" / "percussion.toml").string());
}

TEST_F(KioskStart, WithoutLastGoodSettingsItStartsOnTheShippedDefaults) {
  write_text(settings, "[audio]\nvolume = 0.5\nvolumes = 2\n");  // a misspelt key
  const Result<KioskSetup, std::string> s = start_setup(options, last_good);
  ASSERT_TRUE(s) << s.error();
  EXPECT_DOUBLE_EQ(s->config.audio.volume, AppConfig{}.audio.volume);
  const fs::path shipped = test::config_dir() / "mallet.toml";
  EXPECT_EQ(s->fallback, "the shipped defaults (" + shipped.string() + ")");
  EXPECT_EQ(s->refused.rfind("settings refused: " + settings.string() + ":3:", 0), 0u) << s->refused;
  EXPECT_NE(s->settings_line.find("the shipped defaults"), std::string::npos) << s->settings_line;
}

TEST_F(KioskStart, LastGoodSettingsThatDoNotLoadEitherAreNamedAndTheDefaultsRun) {
  write_text(settings, "[audio\n");
  write_text(last_good, "[audio]\nvolume = 99\n");
  const Result<KioskSetup, std::string> s = start_setup(options, last_good);
  ASSERT_TRUE(s) << s.error();
  EXPECT_NE(s->refused.find("the shipped defaults"), std::string::npos) << s->refused;
  ASSERT_GE(s->problems.size(), 2u);
  EXPECT_EQ(s->problems[1].rfind("its last good settings not used: " + last_good.string() + ":2:", 0), 0u)
      << s->problems[1];
}

TEST_F(KioskStart, AStartSceneThatIsGoneFallsBackToo) {
  write_text(settings, "[scenes]\nstart = \"gone.toml\"\n");
  const Result<KioskSetup, std::string> s = start_setup(options, last_good);
  ASSERT_TRUE(s) << s.error();
  EXPECT_EQ(s->refused.rfind("settings refused: " + settings.string() + ":2:", 0), 0u) << s->refused;
  EXPECT_NE(s->refused.find("no such scene file"), std::string::npos) << s->refused;
}

}  // namespace
}  // namespace mallet::app
