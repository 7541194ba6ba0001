// Drop-ins: mallet.toml.d/*.toml merged over mallet.toml in lexical order, key by key; a bad
// drop-in refused alone with its own file and line; `config show` names each key's file.
#include <fstream>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "core/config/app_config_loader.hpp"
#include "core/config/settings_files.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

namespace fs = std::filesystem;

using test::write_text;

struct DropIns : ::testing::Test {
  fs::path dir = test::scratch_dir();
  fs::path main = dir / "mallet.toml";
  fs::path drop = dir / "mallet.toml.d";
  void SetUp() override {
    write_text(main, "[audio]\nvolume = 0.8\nsample_rate_hz = 48000\n\n[actuator]\ngain = 0.2\n");
  }
};

TEST_F(DropIns, FolderIsTheFileNamePlusD) {
  EXPECT_EQ(config::drop_in_dir_of("/etc/mallet/mallet.toml"), fs::path("/etc/mallet/mallet.toml.d"));
}

TEST_F(DropIns, ListsTomlFilesInLexicalOrderAndNothingElse) {
  write_text(drop / "20-b.toml", "");
  write_text(drop / "10-a.toml", "");
  write_text(drop / "README", "");
  write_text(drop / "9-c.toml", "");  // '9' sorts after '2' byte by byte, as systemd orders them
  fs::create_directories(drop / "30-dir.toml");
  const std::vector<fs::path> files = config::drop_in_files(drop);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].filename(), "10-a.toml");
  EXPECT_EQ(files[1].filename(), "20-b.toml");
  EXPECT_EQ(files[2].filename(), "9-c.toml");
  EXPECT_TRUE(config::drop_in_files(dir / "absent").empty());
}

TEST_F(DropIns, LaterFilesWinKeyByKeyAndTablesMerge) {
  write_text(drop / "10-volume.toml", "[audio]\nvolume = 1.5\n");
  write_text(drop / "20-volume.toml", "[audio]\nvolume = 2.0\n[actuator]\ngain = 0.05\n");
  const config::LoadedSettings s = config::load_settings(main, config::drop_in_files(drop));
  EXPECT_TRUE(s.refused.empty());
  EXPECT_EQ(s.drop_ins.size(), 2u);
  EXPECT_DOUBLE_EQ(s.config.audio.volume, 2.0);
  EXPECT_DOUBLE_EQ(s.config.actuator.gain, 0.05);
  EXPECT_EQ(s.config.audio.sample_rate_hz, 48000);  // untouched keys of a merged table stay
  EXPECT_NE(s.describe().find("+ 2 drop-ins (10-volume.toml, 20-volume.toml)"), std::string::npos) << s.describe();
}

TEST_F(DropIns, ABadDropInIsRefusedWithItsFileAndLineAndTheRestStays) {
  write_text(drop / "10-gain.toml", "[actuator]\ngain = 0.5\n");
  write_text(drop / "20-bad.toml", "# a typo\n[audio]\nvolume = 9\n");          // out of range
  write_text(drop / "30-broken.toml", "[audio\nvolume = 1\n");                     // syntax
  write_text(drop / "40-volume.toml", "[audio]\nvolume = 1.25\n");
  const config::LoadedSettings s = config::load_settings(main, config::drop_in_files(drop));
  ASSERT_EQ(s.refused.size(), 2u);
  EXPECT_EQ(s.refused[0].rfind((drop / "20-bad.toml").string() + ":3:", 0), 0u) << s.refused[0];
  EXPECT_NE(s.refused[0].find("audio.volume"), std::string::npos) << s.refused[0];
  EXPECT_EQ(s.refused[1].rfind((drop / "30-broken.toml").string() + ":1:", 0), 0u) << s.refused[1];
  EXPECT_DOUBLE_EQ(s.config.actuator.gain, 0.5);
  EXPECT_DOUBLE_EQ(s.config.audio.volume, 1.25);
  EXPECT_EQ(s.drop_ins.size(), 2u);
}

TEST_F(DropIns, AMergeThatBreaksAnotherFilesValueIsRefusedAndSaysSo) {
  write_text(main, "[audio.routing]\nchannels = 2\nacoustic = 0\nactuator = 1\n");
  write_text(drop / "10-mono.toml", "[audio.routing]\nchannels = 1\n");  // actuator 1 is now out of range
  const config::LoadedSettings s = config::load_settings(main, config::drop_in_files(drop));
  ASSERT_EQ(s.refused.size(), 1u);
  EXPECT_NE(s.refused[0].find("10-mono.toml"), std::string::npos) << s.refused[0];
  EXPECT_EQ(s.config.audio.routing.channels, 2);
}

TEST_F(DropIns, ABadSettingsFileIsStillAnError) {
  write_text(main, "[audio]\nvolume = -1\n");
  const FileError e = test::file_error_of([&] { config::load_settings(main, {}); });
  EXPECT_EQ(e.file(), main.string());
  EXPECT_EQ(e.line(), 2u);
}

TEST_F(DropIns, WithoutASettingsFileDropInsApplyOverTheDefaults) {
  write_text(drop / "10-volume.toml", "[audio]\nvolume = 0.5\n");
  const config::LoadedSettings s = config::load_settings(std::nullopt, config::drop_in_files(drop));
  EXPECT_DOUBLE_EQ(s.config.audio.volume, 0.5);
  EXPECT_EQ(s.config.actuator.gain, AppConfig{}.actuator.gain);
}

TEST_F(DropIns, ShowNamesEachKeysFileAndParsesBackToTheSameValues) {
  write_text(drop / "10-volume.toml", "[audio]\nvolume = 1.5\n[scenes]\nchoices = [\"wall.toml\", \"a b.toml\"]\n");
  const config::LoadedSettings s = config::load_settings(main, config::drop_in_files(drop));
  const std::string shown = config::show_settings(s);
  EXPECT_NE(shown.find("volume = 1.5  # from " + (drop / "10-volume.toml").string() + ":2"), std::string::npos) << shown;
  EXPECT_NE(shown.find("sample_rate_hz = 48000  # from " + main.string() + ":3"), std::string::npos) << shown;
  EXPECT_NE(shown.find("gain = 0.2  # from " + main.string()), std::string::npos) << shown;
  // What it prints is the merged settings: read back, they are the same.
  const AppConfig back = config::parse_app_config(shown, "shown.toml");
  EXPECT_DOUBLE_EQ(back.audio.volume, 1.5);
  EXPECT_EQ(back.scenes.choices, (std::vector<std::string>{"wall.toml", "a b.toml"}));
  EXPECT_EQ(back.audio.sample_rate_hz, 48000);
}

TEST_F(DropIns, KeptSettingsReadBackAsTheFilesTheyCameFromRelativePathsIncluded) {
  // The kiosk keeps show_settings' text as its last good settings, in its state folder; read
  // back, a relative [metrics] textfile still lies beside the settings it was written in.
  write_text(drop / "10-metrics.toml", "[metrics]\ntextfile = \"mallet.prom\"\n");
  const config::LoadedSettings s = config::load_settings(main, config::drop_in_files(drop));
  write_text(dir / "state" / "kept.toml", config::show_settings(s));
  const config::LoadedSettings kept = config::load_kept_settings(dir / "state" / "kept.toml", main);
  EXPECT_EQ(kept.file, dir / "state" / "kept.toml");
  EXPECT_DOUBLE_EQ(kept.config.audio.volume, 0.8);
  EXPECT_EQ(kept.config.audio.sample_rate_hz, 48000);
  EXPECT_EQ(kept.config.metrics.textfile, (dir / "mallet.prom").string());
  // A bad kept file is a ConfigError naming itself.
  write_text(dir / "state" / "kept.toml", "[audio\n");
  const FileError e = test::file_error_of([&] { config::load_kept_settings(dir / "state" / "kept.toml", main); });
  EXPECT_EQ(e.file(), (dir / "state" / "kept.toml").string());
}

TEST_F(DropIns, AProblemAtAKeptSettingIsNamedInTheOperatorsFileItWasKeptFrom) {
  // A scene choice deleted since was reported against the generated last-good-settings.toml:77
  // (issue 48, item 13): it is named where the operator wrote it, the kept place beside it.
  write_text(drop / "20-scenes.toml", "# the room's scenes\n[scenes]\nchoices = [\"gone.toml\"]\n");
  const config::LoadedSettings s = config::load_settings(main, config::drop_in_files(drop));
  const fs::path kept = dir / "state" / "kept.toml";
  write_text(kept, config::show_settings(s));
  const config::LoadedSettings back = config::load_kept_settings(kept, main);
  const FilePlace& at = back.config.scenes.choices_at;
  ASSERT_EQ(at.file, kept.string());
  const std::string problem = std::string("scene choice skipped: ") + FileError(at, "scenes.choices: gone.toml: no such file").what();
  EXPECT_EQ(config::at_kept_origin(kept, problem),
            "scene choice skipped: " + (drop / "20-scenes.toml").string() + ":3 (kept as " + kept.string() + ":" +
                std::to_string(at.line) + "): scenes.choices: gone.toml: no such file");
  // A place with no origin (the kept file's header), another file's place: as they were.
  EXPECT_EQ(config::at_kept_origin(kept, kept.string() + ":1:1: x"), kept.string() + ":1:1: x");
  EXPECT_EQ(config::at_kept_origin(kept, "/etc/other.toml:3:1: y"), "/etc/other.toml:3:1: y");
}

TEST(ScenesPlaces, TheSettingsLineThatNamesTheScenesIsKept) {
  const AppConfig c = config::parse_app_config("[scenes]\nstart = \"x.toml\"\nchoices = [\"x.toml\"]\n", "m.toml");
  EXPECT_EQ(c.scenes.start_at.file, "m.toml");
  EXPECT_EQ(c.scenes.start_at.line, 2u);
  EXPECT_EQ(c.scenes.choices_at.line, 3u);
  EXPECT_TRUE(AppConfig{}.scenes.start_at.file.empty());
}

}  // namespace
}  // namespace mallet
