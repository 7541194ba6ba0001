// What an operator meets on the command line: the settings with their drop-ins (and
// `mallet config show`), errors that point at the line that caused them, a scene choice that
// is skipped instead of blocking the others, and `mallet doctor` on a machine without a
// remote or a sound card.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "app/kiosk/doctor.hpp"
#include "audio/wav_file.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

using test::write_text;

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void no_display() {
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
}

TEST(ConfigShow, PrintsTheMergedSettingsWithEachKeysFile) {
  const fs::path dir = test::scratch_dir();
  write_text(dir / "mallet.toml", "[audio]\nvolume = 0.8\n[actuator]\ngain = 0.2\n");
  write_text(dir / "mallet.toml.d" / "50-gain.toml", "[actuator]\ngain = 0.05\n");
  const test::CliResult r = test::run_mallet("config show --config " + (dir / "mallet.toml").string() + " 2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("gain = 0.05  # from " + (dir / "mallet.toml.d" / "50-gain.toml").string() + ":2"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("volume = 0.8  # from " + (dir / "mallet.toml").string() + ":2"), std::string::npos)
      << r.output;
  // The output is TOML: Python's own parser reads it back.
  write_text(dir / "shown.toml", r.output);
  const std::string check = "python3 -c \"import tomllib,sys; d=tomllib.load(open(sys.argv[1],'rb'));"
                            "assert d['actuator']['gain']==0.05 and d['audio']['volume']==0.8\" " +
                            (dir / "shown.toml").string();
  EXPECT_EQ(std::system(check.c_str()), 0);
}

TEST(Doctor, OnlyRunsTheChecksNamedInItsOwnOrderAndRefusesAnUnknownName) {
  no_display();
  const fs::path dir = test::scratch_dir();
  // Named out of order: printed in the doctor's order, and nothing else.
  const test::CliResult r = test::run_mallet("doctor --only hidraw,settings,models 2>/dev/null");
  std::istringstream lines(r.output);
  std::string line;
  std::vector<std::string> seen;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string level, name;
    words >> level >> name;
    seen.push_back(name);
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"settings", "models", "hidraw"})) << r.output;
  EXPECT_NE(r.output.find("ok    settings"), std::string::npos) << r.output;
  // The JSON of a choice counts only what ran.
  const test::CliResult j =
      test::run_mallet("doctor --only settings,models --json > " + (dir / "d.json").string() + " 2>/dev/null; exit $?");
  EXPECT_EQ(j.status, 0);
  const std::string check =
      "python3 -c \"import json,sys; d=json.load(open(sys.argv[1])); c=d['checks'];"
      "assert [x['name'] for x in c]==['settings','models'];"
      "assert d['ok']+d['warn']+d['fail']==2\" " +
      (dir / "d.json").string();
  EXPECT_EQ(std::system(check.c_str()), 0);
  // A name that is no check: refused before anything runs, naming the checks.
  const test::CliResult bad = test::run_mallet("doctor --only wiimote,hidrawz 2>&1");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("hidrawz"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("calibration"), std::string::npos) << bad.output;
  EXPECT_EQ(bad.output.find("ok    "), std::string::npos) << bad.output;
}

TEST(ConfigShow, TheKiosksMeasuredDropInsMergeWithTheOperatorsByName) {
  // The display latency the operator confirmed on the page lives in the state folder (the
  // kiosk's service may not write /etc); an operator's drop-in named later still wins.
  const fs::path dir = test::scratch_dir();
  write_text(dir / "mallet.toml", "[timing]\ndisplay_latency_ms = 0.0\n");
  write_text(dir / "state" / "measured.d" / "61-measured-display-latency.toml", "[timing]\ndisplay_latency_ms = 23.4\n");
  const std::string show = "MALLET_STATE_DIR=" + (dir / "state").string() + " " + MALLET_TEST_BINARY +
                           " config show --config " + (dir / "mallet.toml").string() + " 2>/dev/null";
  const test::CliResult measured = test::run_command(show);
  ASSERT_EQ(measured.status, 0) << measured.output;
  EXPECT_NE(measured.output.find("display_latency_ms = 23.4  # from " +
                                 (dir / "state" / "measured.d" / "61-measured-display-latency.toml").string()),
            std::string::npos)
      << measured.output;
  write_text(dir / "mallet.toml.d" / "70-mine.toml", "[timing]\ndisplay_latency_ms = 30.0\n");
  write_text(dir / "mallet.toml.d" / "50-early.toml", "[timing]\ndisplay_latency_ms = 10.0\n");
  const test::CliResult later = test::run_command(show);
  ASSERT_EQ(later.status, 0) << later.output;
  EXPECT_NE(later.output.find("display_latency_ms = 30.0  # from " + (dir / "mallet.toml.d" / "70-mine.toml").string()),
            std::string::npos)
      << later.output;
}

TEST(ConfigShow, ABadDropInIsNamedWithItsLineAndExitsTwoWhileTheRestIsShown) {
  const fs::path dir = test::scratch_dir();
  write_text(dir / "mallet.toml", "[audio]\nvolume = 0.8\n");
  write_text(dir / "d" / "10-bad.toml", "[audio]\nvolume = 12\n");
  write_text(dir / "d" / "20-good.toml", "[actuator]\ngain = 0.3\n");
  const test::CliResult r = test::run_mallet("config show --config " + (dir / "mallet.toml").string() +
                                             " --config-dir " + (dir / "d").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find((dir / "d" / "10-bad.toml").string() + ":2:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("gain = 0.3  # from"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("volume = 0.8  # from"), std::string::npos) << r.output;
}

TEST(OperatorSettings, EveryCommandReadsTheDropInsAndSaysWhichFilesItUsed) {
  const fs::path dir = test::scratch_dir();
  fs::copy(test::config_dir(), dir / "config", fs::copy_options::recursive);
  // A quieter actuator in a drop-in: `simulate`'s actuator channel must follow it, as the kiosk does.
  write_text(dir / "config" / "mallet.toml.d" / "10-gain.toml", "[actuator]\ngain = 0.05\n");
  const std::string settings = (dir / "config" / "mallet.toml").string();
  const test::CliResult r = test::run_mallet("scene describe --scene " + test::percussion_scene().string() +
                                             " > /dev/null; " + std::string(MALLET_TEST_BINARY) +
                                             " render --config " + settings + " --input " +
                                             (test::config_dir() / "trajectories" / "demo.csv").string() +
                                             " --at 0.5 --size 64x36 --out " + (dir / "f.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("mallet render: settings: " + settings + " + 1 drop-in (10-gain.toml)"), std::string::npos)
      << r.output;
}

//! The actuator channel's peak of `mallet simulate` on the demo tune, run with the data folder
//! `data` and no --config (the operator's settings, as the kiosk finds them).
double simulated_actuator_peak(const fs::path& data, const fs::path& out) {
  const std::string cmd = "MALLET_DATA_DIR=" + data.string() + " " + std::string(MALLET_TEST_BINARY) +
                          " simulate --input " + (test::config_dir() / "trajectories" / "demo.csv").string() +
                          " --out " + out.string() + " > " + out.string() + ".said 2>&1";
  const int raw = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(raw), 0) << read(out.string() + ".said");
  const audio::WavData wav = audio::read_wav(out / "audio.wav");
  double peak = 0;
  for (std::size_t i = 1; i < wav.samples.size(); i += static_cast<std::size_t>(wav.channels))
    peak = std::max(peak, static_cast<double>(std::abs(wav.samples[i])));  // channel 1: the actuator
  return peak;
}

TEST(OperatorSettings, SimulateUsesTheOperatorsSettingsAsTheKioskDoes) {
  // An operator turned the actuator down to 0.05 (from 0.2) in a drop-in; simulate used to
  // ignore it and play 4x louder than the kiosk.
  const fs::path dir = test::scratch_dir();
  fs::create_directories(dir / "data");
  fs::copy(test::config_dir(), dir / "data" / "config", fs::copy_options::recursive);
  const double shipped = simulated_actuator_peak(dir / "data", dir / "shipped");
  write_text(dir / "data" / "config" / "mallet.toml.d" / "50-gain.toml", "[actuator]\ngain = 0.05\n");
  const double turned_down = simulated_actuator_peak(dir / "data", dir / "turned-down");
  ASSERT_GT(shipped, 0.01);
  EXPECT_NEAR(turned_down / shipped, 0.25, 1e-3);
  EXPECT_NE(read(dir.string() + "/turned-down.said").find("mallet simulate: settings: " +
                                                           (dir / "data" / "config" / "mallet.toml").string() +
                                                           " + 1 drop-in (50-gain.toml)"),
            std::string::npos)
      << read(dir.string() + "/turned-down.said");
}

TEST(OperatorSettings, AMissingStartSceneIsReportedAgainstTheSettingsLineThatNamesIt) {
  no_display();
  const fs::path dir = test::scratch_dir();
  write_text(dir / "mallet.toml", "# the operator's settings\n[scenes]\nstart = \"gone.toml\"\n");
  const test::CliResult r = test::run_mallet("run --headless --seconds 0.1 --config " + (dir / "mallet.toml").string() +
                                             " --out " + (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("mallet: " + (dir / "mallet.toml").string() + ":3:9: scenes.start: \"gone.toml\": no such scene file"),
            std::string::npos)
      << r.output;
}

TEST(OperatorSettings, ABadSceneChoiceIsSkippedWithItsReasonAndTheKioskRuns) {
  no_display();
  const fs::path dir = test::scratch_dir();
  write_text(dir / "mallet.toml", "[scenes]\nstart = \"percussion.toml\"\nchoices = [\"percussion.toml\", \"gone.toml\", \"wall.toml\"]\n");
  const test::CliResult r = test::run_mallet("run --headless --seconds 0.2 --size 64x36 --config " +
                                             (dir / "mallet.toml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string log = read(dir / "out" / "log.txt");
  EXPECT_NE(log.find("warning: scene choice skipped: " + (dir / "mallet.toml").string() + ":3:"), std::string::npos)
      << log;
  EXPECT_NE(log.find("\"gone.toml\": no such scene file"), std::string::npos) << log;
  EXPECT_EQ(log.find("wall.toml\": no such"), std::string::npos) << log;
}

TEST(OperatorSettings, ABrokenModelNamesTheSceneKeyThatChoseIt) {
  no_display();
  const fs::path dir = test::scratch_dir();
  fs::copy(test::config_dir(), dir / "config", fs::copy_options::recursive);
  fs::copy(test::source_dir() / "models", dir / "models", fs::copy_options::recursive);
  write_text(dir / "models" / "metal_bar.glb", "not a glTF file");
  // The models are found through the data folder: this copy, with its settings and scenes.
  const std::string cmd = "MALLET_DATA_DIR=" + dir.string() + " " + std::string(MALLET_TEST_BINARY) +
                          " run --headless --seconds 0.1 --size 64x36 --out " + (dir / "out2").string() + " > " +
                          (dir / "said.txt").string() + " 2>&1";
  const int raw = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(raw), 2) << read(dir / "said.txt");
  const std::string said = read(dir / "said.txt");
  EXPECT_NE(said.find((dir / "config" / "scenes" / "percussion.toml").string() + ":"), std::string::npos) << said;
  EXPECT_NE(said.find(".bar_model = \"metal_bar.glb\": " + (dir / "models" / "metal_bar.glb").string()),
            std::string::npos)
      << said;
}

TEST(Doctor, SaysWhatThisMachineLacksOneLineEachAndExitsOneOnAFailure) {
  no_display();
  const fs::path dir = test::scratch_dir();
  const test::CliResult r = test::run_mallet("doctor 2>/dev/null");
  const char* names[] = {"vulkan", "compositor", "audio", "wiimote", "camera", "settings", "models", "soundfont", "languages",
                         "language", "actuator", "latency", "display", "hidraw", "calibration", "disk", "service", "watchdog"};
  std::istringstream lines(r.output);
  std::string line;
  std::vector<std::string> seen;
  bool failed = false;
  while (std::getline(lines, line)) {
    const std::string level = line.substr(0, line.find(' '));
    ASSERT_TRUE(level == "ok" || level == "warn" || level == "fail") << line;
    failed |= level == "fail";
    std::istringstream words(line);
    std::string l, name;
    words >> l >> name;
    seen.push_back(name);
    if (level != "ok") {
      EXPECT_NE(line.find(" -> fix: "), std::string::npos) << "a problem comes with its fix: " << line;
    }
  }
  EXPECT_EQ(seen, std::vector<std::string>(std::begin(names), std::end(names))) << r.output;
  EXPECT_EQ(r.status, failed ? 1 : 0) << r.output;
  // No Wii Remote here, and the shipped settings say "auto": the wiimote line is the one the
  // operator page's D shows too (one wording, app/kiosk/doctor.hpp: wiimote_without_remote).
  const DoctorCheck no_remote = wiimote_without_remote("auto");
  EXPECT_EQ(no_remote.level, CheckLevel::warn);
  const std::size_t at = r.output.find("warn  wiimote ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string wiimote_line = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_NE(wiimote_line.find(no_remote.found + " -> fix: " + no_remote.fix), std::string::npos) << wiimote_line;
  EXPECT_EQ(wiimote_without_remote("wiimote").level, CheckLevel::fail);
  EXPECT_EQ(wiimote_without_remote("mouse").found, "not used: [input] source = \"mouse\"");
  // The shipped settings, scenes and models are all readable.
  EXPECT_NE(r.output.find("ok    settings"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ok    models"), std::string::npos) << r.output;
  // Every shipped catalogue is found (the test runner points at the catalogues this build
  // made), and the language shown (English) needs nothing.
  EXPECT_NE(r.output.find("ok    languages    en, de, fr, ja, zh, ko, ar, he, hi: catalogues in "), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("ok    language     en: the texts as written"), std::string::npos) << r.output;
  // No actuator calibration and no latency measured here: each fine, saying how.
  EXPECT_NE(r.output.find("ok    actuator     not measured ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ok    latency      never measured ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ok    display      never measured ("), std::string::npos) << r.output;
  // The JSON says the same, and Python's parser reads it.
  const test::CliResult j = test::run_mallet("doctor --json > " + (dir / "d.json").string() + " 2>/dev/null; exit $?");
  EXPECT_EQ(j.status, r.status);
  const std::string check =
      "python3 -c \"import json,sys; d=json.load(open(sys.argv[1])); c=d['checks'];"
      "assert [x['name'] for x in c]==['vulkan','compositor','audio','wiimote','camera','settings','models','soundfont','languages','language','actuator','latency','display','hidraw',"
      "'calibration','disk','service','watchdog'];"
      "assert all(x['status'] in ('ok','warn','fail') for x in c);"
      "assert d['fail']==sum(x['status']=='fail' for x in c) and d['ok']+d['warn']+d['fail']==len(c)\" " +
      (dir / "d.json").string();
  EXPECT_EQ(std::system(check.c_str()), 0);
}

}  // namespace
}  // namespace mallet::app
