// `mallet render` as a researcher's script runs it.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/image.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

std::filesystem::path still_trajectory(const std::filesystem::path& dir) {
  std::ofstream(dir / "t.csv") << "t,x,y\n0,0.3,0.2\n0.5,0.3,0.9\n1.0,0.3,0.2\n";
  return dir / "t.csv";
}

TEST(RenderCli, OneFrameAtATimeIsAPngOfTheAskedSize) {
  const auto dir = test::scratch_dir();
  const test::CliResult r = test::run_mallet("render --input " + still_trajectory(dir).string() +
                                             " --at 0.6 --size 200x120 --msaa 1 --out " + (dir / "f.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const render::Image img = render::read_png(dir / "f.png");
  EXPECT_EQ(img.width, 200);
  EXPECT_EQ(img.height, 120);
}

TEST(RenderCli, ASequenceHasOneFramePerTickIncludingBothEnds) {
  const auto dir = test::scratch_dir();
  const test::CliResult r = test::run_mallet("render --input " + still_trajectory(dir).string() +
                                             " --fps 10 --from 0.2 --to 0.5 --size 64x36 --msaa 1 --out-dir " +
                                             (dir / "seq").string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (int k = 0; k <= 3; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", k);
    EXPECT_TRUE(std::filesystem::exists(dir / "seq" / name)) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "seq" / "frame_000004.png"));
  EXPECT_NE(r.output.find("t=0.300000000"), std::string::npos) << r.output;
}

TEST(RenderCli, BadSizeOrUnofferedAntialiasingIsAClearError) {
  const auto dir = test::scratch_dir();
  const auto traj = still_trajectory(dir).string();
  test::CliResult r = test::run_mallet("render --input " + traj + " --at 0 --size 12x9000 --out " +
                                       (dir / "f.png").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  r = test::run_mallet("render --input " + traj + " --at 0 --size 64x36 --msaa 3 --out " + (dir / "f.png").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--msaa"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "f.png"));
}

TEST(RenderCli, ATimeTheClockCannotHoldIsRefusedByTheFlagsCheck) {
  const auto dir = test::scratch_dir();
  const auto traj = still_trajectory(dir).string();
  for (const std::string at : {"nan", "inf", "1e300"}) {
    const test::CliResult r = test::run_mallet("render --input " + traj + " --at " + at + " --out " +
                                               (dir / "f.png").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("--at: must be a finite number of seconds, got " + at), std::string::npos) << r.output;
  }
  const test::CliResult r = test::run_mallet("render --input " + traj + " --fps 10 --from -1e12 --to 0 --out-dir " +
                                             (dir / "seq").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--from: must be a finite number of seconds"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "f.png"));
}

TEST(RenderCli, AMissingModelNamesTheFileAndDrawsNothing) {
  const auto dir = test::scratch_dir();
  std::filesystem::copy(test::config_dir(), dir / "config", std::filesystem::copy_options::recursive);
  std::filesystem::create_directories(dir / "models");  // empty: no model at all
  const std::string env = "MALLET_DATA_DIR=" + dir.string() + " ";
  const std::string cmd = env + MALLET_TEST_BINARY + " render --scene " +
                          (dir / "config/scenes/percussion.toml").string() + " --input " +
                          still_trajectory(dir).string() + " --at 0 --size 64x36 --out " +
                          (dir / "f.png").string() + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int status = pclose(p);
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find(".glb"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "f.png"));
}

//! The events.csv rows' target ids.
std::vector<int> struck_targets(const std::filesystem::path& events) {
  std::ifstream in(events);
  std::string line;
  std::getline(in, line);  // the header
  std::vector<int> out;
  while (std::getline(in, line))
    if (const std::size_t a = line.find(','); a != std::string::npos) out.push_back(std::stoi(line.substr(a + 1)));
  return out;
}

TEST(LayoutCli, APortraitScriptStrikesItsBarsWhenSimulatedInThePortraitLayoutAndRendersStacked) {
  // A researcher reproducing a portrait kiosk: `mallet trajectory --layout portrait` aims at
  // the stacked bars, and `mallet simulate --layout portrait` strikes exactly them; the same
  // script in the landscape layout (where the bars are elsewhere) does not.
  const auto dir = test::scratch_dir();
  test::CliResult r = test::run_mallet("trajectory --layout portrait --targets 10,2,13 --space world --interval 0.8 --out " +
                                       (dir / "p.csv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  r = test::run_mallet("simulate --layout portrait --input-space world --input " + (dir / "p.csv").string() +
                       " --out " + (dir / "portrait").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(struck_targets(dir / "portrait" / "events.csv"), (std::vector<int>{10, 2, 13}));
  r = test::run_mallet("simulate --input-space world --input " + (dir / "p.csv").string() + " --out " +
                       (dir / "landscape").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(struck_targets(dir / "landscape" / "events.csv"), (std::vector<int>{10, 2, 13}));
  // `render` lays the scene out for its --size as the kiosk does (auto): a portrait image
  // differs from the landscape layout framed on the same image.
  for (const char* layout : {"auto", "landscape"}) {
    r = test::run_mallet("render --input-space world --input " + (dir / "p.csv").string() +
                         " --at 0.5 --size 90x160 --msaa 1 --layout " + layout + " --out " +
                         (dir / (std::string(layout) + ".png")).string());
    ASSERT_EQ(r.status, 0) << r.output;
  }
  EXPECT_NE(render::read_png(dir / "auto.png").rgba, render::read_png(dir / "landscape.png").rgba);
  r = test::run_mallet("simulate --layout sideways --input " + (dir / "p.csv").string() + " --out " +
                       (dir / "x").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--layout"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace mallet::app
