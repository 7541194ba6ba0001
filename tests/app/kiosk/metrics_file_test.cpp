// [metrics] textfile: the headless run's and the window kiosk's files parse with Prometheus'
// own Python parser and count what their logs say; the writer survives a folder that is not
// there; restarts are counted in the state folder; strikes are tallied from several threads
// without locks.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "app/kiosk/metrics_file.hpp"
#include "run_cli.hpp"
#include "child_process.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

//! Debian's interpreter first: python3-prometheus-client installs into its dist-packages.
std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

test::CliResult run_command(const std::string& command) {
  test::CliResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename());
  return out;
}

TEST(MetricsFile, TheHeadlessRunsFileParsesAndCountsTheStrikesAndFramesOfItsLog) {
  const fs::path dir = test::scratch_dir();
  fs::create_directories(dir / "node-exporter");
  const fs::path prom = dir / "node-exporter" / "mallet.prom";
  { std::ofstream(dir / "mallet.toml") << "[metrics]\ntextfile = \"" << prom.string() << "\"\ninterval_s = 1\n"; }
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  const test::CliResult r = test::run_mallet("run --headless --seconds 4 --size 160x90 --config " +
                                             (dir / "mallet.toml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(fs::exists(prom)) << r.output;
  // Replaced by rename: no temporary file is left beside it.
  EXPECT_EQ(files_in(dir / "node-exporter"), std::vector<fs::path>{"mallet.prom"});

  const std::string checker = (test::source_dir() / "tests/app/kiosk/check_metrics.py").string();
  const test::CliResult check =
      run_command(python() + " " + checker + " " + prom.string() + " " + (dir / "out" / "log.txt").string());
  std::printf("%s", check.output.c_str());  // what was compared, in the test's log
  EXPECT_EQ(check.status, 0) << check.output << "\n(python3-prometheus-client installed? see packaging/deps-build.txt)";
  EXPECT_NE(check.output.find("check_metrics: ok"), std::string::npos) << check.output;

  const std::string text = read_text(prom);
  EXPECT_NE(text.find("mallet_build_info{version=\""), std::string::npos) << text;
  EXPECT_NE(text.find("mallet_state{state=\"attract\"} 1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("mallet_restarts_total 0\n"), std::string::npos) << "the headless run is not a start:\n" << text;
  EXPECT_NE(text.find("mallet_uptime_seconds 4\n"), std::string::npos) << "the simulated clock:\n" << text;
}

using test::child_preload;

TEST(MetricsFile, TheWindowKiosksFileCountsTheFramesAndStrikesItsLogSays) {
  ASSERT_EQ(std::system("command -v xvfb-run >/dev/null"), 0) << "xvfb-run is missing (Debian package xvfb)";
  const fs::path dir = test::scratch_dir();
  const fs::path prom = dir / "mallet.prom";
  {
    std::ofstream(dir / "mallet.toml") << "[metrics]\ntextfile = \"mallet.prom\"\ninterval_s = 1\n"
                                       << "[input]\nsource = \"mouse\"\nmouse = \"window\"\n";
  }
  // The ghost plays from the start (--idle-after 1); the run's length is the kiosk's own
  // --quit-after, nothing here is timed.
  const std::string cmd = child_preload() + "MALLET_STATE_DIR='" + (dir / "state").string() +
                          "' xvfb-run -a -s '-screen 0 1024x768x24' " + MALLET_TEST_BINARY +
                          " run --windowed --size 320x180 --idle-after 1 --quit-after 3 --device llvmpipe --config " +
                          (dir / "mallet.toml").string() + " > " + (dir / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "log.txt");
  ASSERT_TRUE(fs::exists(prom)) << "relative to the settings file's folder\n" << read_text(dir / "log.txt");
  const std::string checker = (test::source_dir() / "tests/app/kiosk/check_metrics.py").string();
  const test::CliResult check =
      run_command(python() + " " + checker + " " + prom.string() + " " + (dir / "log.txt").string());
  std::printf("%s", check.output.c_str());
  EXPECT_EQ(check.status, 0) << check.output << "\n" << read_text(dir / "log.txt");
  // The first start of a kiosk with metrics: counted in its state folder, none before it.
  EXPECT_EQ(read_text(dir / "state" / "kiosk-starts"), "1\n");
  const std::string text = read_text(prom);
  EXPECT_NE(text.find("mallet_restarts_total 0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("mallet_remote_connected 0\n"), std::string::npos) << "the mouse is the input:\n" << text;
}

TEST(MetricsFile, AFailedWriteIsOneLineAndIsTriedAgainAtTheNextInterval) {
  const fs::path dir = test::scratch_dir();
  std::vector<std::string> warnings, notes;
  MetricsFile file(
      nullptr, [&](const std::string& l) { warnings.push_back(l); }, [&](const std::string& l) { notes.push_back(l); });
  KioskMetrics metrics;
  EXPECT_FALSE(file.due(0)) << "off until configured";
  file.configure({(dir / "missing" / "mallet.prom").string(), 2.0});
  ASSERT_TRUE(file.due(0));
  EXPECT_FALSE(file.write(metrics, 0));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("missing/mallet.prom"), std::string::npos) << warnings[0];
  EXPECT_EQ(warnings[0].find('\n'), std::string::npos) << "one line";

  EXPECT_FALSE(file.due(kNanosPerSecond));
  ASSERT_TRUE(file.due(2 * kNanosPerSecond));
  EXPECT_FALSE(file.write(metrics, 2 * kNanosPerSecond));
  EXPECT_EQ(warnings.size(), 1u) << "the same failure is not said again";

  fs::create_directories(dir / "missing");
  ASSERT_TRUE(file.due(4 * kNanosPerSecond));
  EXPECT_TRUE(file.write(metrics, 4 * kNanosPerSecond));
  EXPECT_EQ(notes.size(), 1u);
  EXPECT_EQ(read_text(dir / "missing" / "mallet.prom"), render_prometheus_text(metrics));
  EXPECT_EQ(files_in(dir / "missing"), std::vector<fs::path>{"mallet.prom"});
}

TEST(MetricsFile, RestartsAreTheStartsCountedBeforeInTheStateFolder) {
  const fs::path state = test::scratch_dir() / "state";  // created by the first count
  std::vector<std::string> warnings;
  const auto warn = [&](const std::string& l) { warnings.push_back(l); };
  const MetricsConfig on{(state.parent_path() / "mallet.prom").string(), 15.0};
  StateFolder folder(state, warn, warn);

  {  // Without a metrics file nothing is written in the state folder.
    MetricsFile off(&folder, warn, warn);
    off.configure({});
    EXPECT_FALSE(fs::exists(state / "kiosk-starts"));
  }
  for (std::uint64_t run = 0; run < 3; ++run) {
    MetricsFile file(&folder, warn, warn);
    file.configure(on);
    file.configure(on);  // a reload is not a start
    EXPECT_EQ(file.restarts(), run);
    KioskMetrics m;
    ASSERT_TRUE(file.write(m, 0));
    EXPECT_EQ(m.restarts, run);
    EXPECT_NE(read_text(on.textfile).find("mallet_restarts_total " + std::to_string(run) + "\n"), std::string::npos);
  }
  EXPECT_EQ(read_text(state / "kiosk-starts"), "3\n");
  EXPECT_TRUE(warnings.empty());

  { std::ofstream(state / "kiosk-starts") << "many\n"; }
  EXPECT_EQ(count_kiosk_start(folder, warn), 0u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("kiosk-starts:1:"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("(the file is kept as " + (state / "kiosk-starts.bad").string() + ")"), std::string::npos)
      << warnings[0];
  EXPECT_EQ(read_text(state / "kiosk-starts.bad"), "many\n");  // for the operator
  EXPECT_EQ(read_text(state / "kiosk-starts"), "1\n");
}

TEST(MetricsFile, StrikesAreTalliedByInstrumentAndMaterialFromSeveralThreads) {
  const Scene& scene = test::percussion();
  StrikeTally tally(scene);
  std::vector<std::thread> routes;  // the main thread's, the remote's and the mouse's
  for (int r = 0; r < 3; ++r)
    routes.emplace_back([&, r] {
      for (int i = 0; i < 1000; ++i) tally.record(test::strike(r == 2 ? 12 : i % 2, 0, 1.0));
    });
  for (std::thread& t : routes) t.join();
  Impact outside = test::strike(0, 0, 1.0);
  outside.target = 99;  // not in the scene: not counted, not a crash
  tally.record(outside);

  StrikeCounts counts;
  seed_strike_labels(scene, counts);
  ASSERT_EQ(counts.size(), 2u);  // both instruments exist from the start, at 0
  tally.add_to(counts);
  EXPECT_EQ((counts[{"xylophone", "wood"}]), 2000u);
  EXPECT_EQ((counts[{"glockenspiel", "metal"}]), 1000u);
  EXPECT_EQ(counts.size(), 2u);
}

TEST(MetricsFile, TheWallHasASeriesForEachOfItsMaterials) {
  const Scene& wall = test::wall();
  StrikeCounts counts;
  seed_strike_labels(wall, counts);
  EXPECT_EQ(counts.size(), wall.wall_materials.size());
  for (int m : wall.wall_materials)
    EXPECT_EQ(counts.count({"wall", wall.materials[static_cast<std::size_t>(m)].name}), 1u);
}

}  // namespace
}  // namespace mallet::app
