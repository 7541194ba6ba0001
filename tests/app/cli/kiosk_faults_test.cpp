// The kiosk against what a museum's machine does to it: a broken settings file at boot (it
// comes up on its last good settings or the shipped defaults, and says so), a state folder it
// cannot write (it plays on, says so once), and `mallet doctor` saying both, and which
// renderer the kiosk's compositor uses. The window kiosk runs for real under its own Xvfb;
// nothing here is timed (its length is the kiosk's own --quit-after).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;
using test::child_preload;
using test::slurp;

using test::write_text;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

//! `mallet run` in a window under its own Xvfb for 2.5 s, its state in `state`; the
//! exit status, its stderr and stdout in `log`.
int run_window_kiosk(const fs::path& settings, const fs::path& state, const fs::path& log,
                     const std::string& size = "320x180") {
  const std::string cmd = child_preload() + "MALLET_STATE_DIR='" + state.string() +
                          "' xvfb-run -a -s '-screen 0 1024x768x24' " + MALLET_TEST_BINARY +
                          " run --windowed --size " + size + " --idle-after 1 --quit-after 2.5 --device llvmpipe --config " +
                          settings.string() + " > " + log.string() + " 2>&1";
  const int raw = std::system(cmd.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

//! `mallet ARGS` with one more variable in its environment ("NAME=value").
test::CliResult run_with(const std::string& variable, const std::string& args) {
  return test::run_command("env '" + variable + "' " + std::string(MALLET_TEST_BINARY) + " " + args);
}

void unset_display() {
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
}

TEST(KioskFaults, ABrokenSettingsFileAtStartRunsTheLastGoodSettingsAndSaysSoInOneLine) {
  ASSERT_EQ(std::system("command -v xvfb-run >/dev/null"), 0) << "xvfb-run is missing (Debian package xvfb)";
  const fs::path dir = test::scratch_dir();
  const fs::path settings = dir / "etc" / "mallet.toml";
  const fs::path state = dir / "state";
  const std::string input = "[input]\nsource = \"mouse\"\nmouse = \"window\"\n";

  // A start on good settings keeps them.
  write_text(settings, input + "[audio]\nvolume = 0.5\n");
  ASSERT_EQ(run_window_kiosk(settings, state, dir / "good.txt"), 0) << slurp(dir / "good.txt");
  const std::string kept = slurp(state / "last-good-settings.toml");
  EXPECT_NE(kept.find("volume = 0.5  # from " + settings.string() + ":5"), std::string::npos) << kept;

  // Broken: the kiosk comes up all the same, on them, and says so as an error.
  write_text(settings, input + "[audio]\nvolume = \"loud\n");
  ASSERT_EQ(run_window_kiosk(settings, state, dir / "broken.txt"), 0) << slurp(dir / "broken.txt");
  const std::string log = slurp(dir / "broken.txt");
  EXPECT_NE(log.find("<3>settings refused: " + settings.string() + ":5:"), std::string::npos) << log;
  EXPECT_NE(log.find("; the kiosk runs on its last good settings (" + (state / "last-good-settings.toml").string() +
                     ")"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("strike t="), std::string::npos) << "it plays:\n" << log;
  EXPECT_EQ(slurp(state / "last-good-settings.toml"), kept) << "a fallback is not kept over the last good settings";

  // Without last good settings: the shipped defaults.
  fs::remove(state / "last-good-settings.toml");
  ASSERT_EQ(run_window_kiosk(settings, state, dir / "defaults.txt"), 0) << slurp(dir / "defaults.txt");
  EXPECT_NE(slurp(dir / "defaults.txt").find("; the kiosk runs on the shipped defaults ("), std::string::npos)
      << slurp(dir / "defaults.txt");
}

TEST(KioskLayout, APortraitWindowLaysTheInstrumentsOutStackedAndTheGhostStrikesThem) {
  ASSERT_EQ(std::system("command -v xvfb-run >/dev/null"), 0) << "xvfb-run is missing (Debian package xvfb)";
  const fs::path dir = test::scratch_dir();
  const fs::path settings = dir / "etc" / "mallet.toml";
  write_text(settings, "[input]\nsource = \"mouse\"\nmouse = \"window\"\n");
  ASSERT_EQ(run_window_kiosk(settings, dir / "state", dir / "portrait.txt", "180x320"), 0) << slurp(dir / "portrait.txt");
  const std::string portrait = slurp(dir / "portrait.txt");
  EXPECT_NE(portrait.find("scene: laid out portrait for the screen's 0.56:1"), std::string::npos) << portrait;
  EXPECT_NE(portrait.find("strike t="), std::string::npos) << "the ghost plays:\n" << portrait;
  std::istringstream lines(portrait);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("strike t=") != std::string::npos) {  // the phrase opens on the upper row, struck from above
      EXPECT_NE(line.find("xylophone"), std::string::npos) << line;
    }
  }
  ASSERT_EQ(run_window_kiosk(settings, dir / "state", dir / "landscape.txt"), 0) << slurp(dir / "landscape.txt");
  EXPECT_EQ(slurp(dir / "landscape.txt").find("laid out portrait"), std::string::npos) << slurp(dir / "landscape.txt");
  // The headless run lays its image out as the window does.
  const test::CliResult headless = test::run_command(std::string(MALLET_TEST_BINARY) +
                                                     " run --headless --seconds 0.1 --size 36x64 --config " +
                                                     settings.string() + " --out " + (dir / "headless").string());
  ASSERT_EQ(headless.status, 0) << headless.output;
  EXPECT_NE(slurp(dir / "headless" / "log.txt").find("percussion.toml, laid out portrait"), std::string::npos)
      << slurp(dir / "headless" / "log.txt");
}

TEST(KioskFaults, HeadlessAndTheOtherCommandsStillRefuseABrokenSettingsFileWithExitTwo) {
  unset_display();
  const fs::path dir = test::scratch_dir();
  const fs::path settings = dir / "mallet.toml";
  write_text(settings, "# the operator's\n[audio]\nvolume = \"loud\n");
  // Even with last good settings kept: a researcher's run does not fall back.
  write_text(dir / "state" / "last-good-settings.toml", "[audio]\nvolume = 0.5\n");
  for (const std::string& command :
       {"run --headless --seconds 0.1 --size 64x36 --out " + (dir / "out").string(), std::string("config show"),
        "simulate --input " + (test::config_dir() / "trajectories" / "demo.csv").string() + " --out " +
            (dir / "sim").string()}) {
    const test::CliResult r = run_with("MALLET_STATE_DIR=" + (dir / "state").string(),
                                       command + " --config " + settings.string());
    EXPECT_EQ(r.status, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(settings.string() + ":3:"), std::string::npos) << command << "\n" << r.output;
    EXPECT_EQ(r.output.find("last good"), std::string::npos) << command << "\n" << r.output;
  }
}

TEST(KioskFaults, AStateFolderThatCannotBeWrittenIsSaidOnceAndTheKioskPlaysOn) {
  ASSERT_EQ(std::system("command -v xvfb-run >/dev/null"), 0) << "xvfb-run is missing (Debian package xvfb)";
  const fs::path dir = test::scratch_dir();
  // A regular file where the state folder should be: nothing can be written into it, as on a
  // full or read-only disk (root ignores permissions, so this is how a test as root gets it).
  const fs::path state = dir / "state";
  write_text(state, "not a folder\n");
  const fs::path settings = dir / "mallet.toml";
  write_text(settings, "[input]\nsource = \"mouse\"\nmouse = \"window\"\n[metrics]\ntextfile = \"mallet.prom\"\n"
                  "interval_s = 1\n");
  ASSERT_EQ(run_window_kiosk(settings, state, dir / "log.txt"), 0) << slurp(dir / "log.txt");
  const std::string log = slurp(dir / "log.txt");
  // Two writes failed (the count of starts, the last good settings): one warning.
  EXPECT_EQ(count(log, "<4>state folder " + state.string() + " cannot be written ("), 1u) << log;
  EXPECT_NE(log.find("strike t="), std::string::npos) << "it plays:\n" << log;
  EXPECT_EQ(slurp(state), "not a folder\n");
  const std::string prom = slurp(dir / "mallet.prom");
  EXPECT_NE(prom.find("\nmallet_state_folder_writable 0\n"), std::string::npos) << prom;
  EXPECT_NE(prom.find("\nmallet_settings_refused 0\n"), std::string::npos) << prom;

  // The doctor, alone, finds it too, naming the folder.
  unset_display();
  const test::CliResult d = run_with("MALLET_STATE_DIR=" + state.string(), "doctor --config " + settings.string());
  EXPECT_NE(d.output.find("fail  disk         state folder: "), std::string::npos) << d.output;
  EXPECT_NE(d.output.find(state.string() + " is not a folder"), std::string::npos) << d.output;
}

TEST(KioskFaults, DoctorSaysTheBrokenSettingsLineAndWhatTheKioskRunsOnMeanwhile) {
  unset_display();
  const fs::path dir = test::scratch_dir();
  const fs::path settings = dir / "mallet.toml";
  write_text(settings, "[audio]\nvolume = 12\n");
  const test::CliResult r =
      run_with("MALLET_STATE_DIR=" + (dir / "state").string(), "doctor --config " + settings.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("fail  settings     " + settings.string() + ":2:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("meanwhile the kiosk runs on the shipped defaults ("), std::string::npos) << r.output;
}

TEST(KioskFaults, DoctorPrintsTheCompositorsRendererForTheSessionsStartScript) {
  unset_display();
  // An operator's WLR_RENDERER wins, whatever /dev/dri holds.
  test::CliResult r = run_with("WLR_RENDERER=pixman", "doctor --print-renderer");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "pixman\n");
  // Else this machine's rule: one word, pixman without a render node, gles2 with one.
  r = run_with("WLR_RENDERER=", "doctor --print-renderer");
  EXPECT_EQ(r.status, 0) << r.output;
  std::error_code ec;
  bool render_node = false;
  for (const fs::directory_entry& e : fs::directory_iterator("/dev/dri", ec))
    render_node |= e.path().filename().string().rfind("renderD", 0) == 0;
  EXPECT_EQ(r.output, render_node ? "gles2\n" : "pixman\n");
}

}  // namespace
}  // namespace mallet::app
