// `mallet calibrate fit` then `mallet calibrate map`, through the real binary: the map
// reproduces the known homography, exit statuses follow the contract (0 ok, 2 bad input),
// and a malformed CSV line is named.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/calibration_file.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

// A known camera → normalised screen map with perspective and a mirror in x.
const Homography kTruth{{-1.1e-3, 5.0e-5, 1.05, 3.0e-5, 1.45e-3, -0.08, 1.5e-4, -2.0e-4, 1.0}};

std::string points_csv(const std::vector<Vec2>& screen) {
  const Homography to_cam = *kTruth.inverse();
  std::string out = "# made by calibrate_cli_test\ncam_x,cam_y,screen_x,screen_y\n";
  char buf[160];
  for (Vec2 s : screen) {
    const Vec2 c = to_cam.map(s);
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g,%.17g\n", c.x, c.y, s.x, s.y);
    out += buf;
  }
  return out;
}

const std::vector<Vec2> kGrid{{0.1, 0.1}, {0.5, 0.1}, {0.9, 0.1}, {0.1, 0.5}, {0.5, 0.5},
                              {0.9, 0.5}, {0.1, 0.9}, {0.5, 0.9}, {0.9, 0.9}};

TEST(CalibrateCli, FitThenMapReproducesTheHomography) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "points.csv") << points_csv(kGrid);
  const auto cal = dir / "cal.toml";
  const test::CliResult fit = test::run_mallet("calibrate fit --points " + (dir / "points.csv").string() + " --out " +
                                               cal.string() + " --remote 00:1f:32:aa:bb:cc");
  ASSERT_EQ(fit.status, 0) << fit.output;
  EXPECT_NE(fit.output.find("camera -> normalised screen"), std::string::npos) << fit.output;
  EXPECT_NE(fit.output.find("screen_px"), std::string::npos) << fit.output;
  EXPECT_NE(fit.output.find("(9 points)"), std::string::npos) << fit.output;
  EXPECT_NE(fit.output.find("wrote " + cal.string()), std::string::npos) << fit.output;
  const Calibration loaded = load_calibration(cal);
  EXPECT_EQ(loaded.points, 9);
  EXPECT_EQ(loaded.remote, "00:1f:32:aa:bb:cc");
  EXPECT_LT(loaded.max_error_screen_px, 1e-6);

  const Homography to_cam = *kTruth.inverse();
  for (Vec2 s : {Vec2{0.3, 0.7}, Vec2{0.0, 0.0}, Vec2{1.0, 1.0}, Vec2{0.77, 0.21}}) {
    const Vec2 c = to_cam.map(s);
    char args[64];
    std::snprintf(args, sizeof args, " %.17g %.17g", c.x, c.y);
    const test::CliResult map = test::run_mallet("calibrate map --calibration " + cal.string() + args);
    ASSERT_EQ(map.status, 0) << map.output;
    std::istringstream line(map.output);
    double x = NAN, y = NAN;
    std::string rest;
    line >> x >> y;
    EXPECT_FALSE(line >> rest) << "one line, two numbers: " << map.output;
    EXPECT_NEAR(x, s.x, 1e-9) << map.output;
    EXPECT_NEAR(y, s.y, 1e-9) << map.output;
    // Enough digits to round-trip: exactly what the loaded calibration computes.
    const Vec2 exact = loaded.camera_to_screen.map({std::strtod(args, nullptr), std::strtod(std::strchr(args + 1, ' '), nullptr)});
    EXPECT_EQ(x, exact.x);
    EXPECT_EQ(y, exact.y);
  }
}

TEST(CalibrateCli, AMalformedLineExitsTwoNamingTheLine) {
  const auto dir = test::scratch_dir();
  std::string csv = points_csv(kGrid);
  // Line 5 (after a comment, the header and two rows) loses a field.
  std::size_t at = 0;
  for (int i = 0; i < 4; ++i) at = csv.find('\n', at) + 1;
  csv.insert(at, "12,34,0.5\n");
  std::ofstream(dir / "points.csv") << csv;
  const test::CliResult r = test::run_mallet("calibrate fit --points " + (dir / "points.csv").string() + " --out " +
                                             (dir / "cal.toml").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("points.csv:5: expected 4 fields, got 3"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "cal.toml"));

  std::ofstream(dir / "nohead.csv") << "1,2,0,0\n";
  const test::CliResult h = test::run_mallet("calibrate fit --points " + (dir / "nohead.csv").string() + " --out " +
                                             (dir / "cal.toml").string());
  EXPECT_EQ(h.status, 2);
  EXPECT_NE(h.output.find("nohead.csv:1: unknown column \"1\""), std::string::npos) << h.output;

  std::ofstream(dir / "range.csv") << "cam_x,cam_y,screen_x,screen_y\n10,1023,0,0\n";
  const test::CliResult g = test::run_mallet("calibrate fit --points " + (dir / "range.csv").string() + " --out " +
                                             (dir / "cal.toml").string());
  EXPECT_EQ(g.status, 2);
  EXPECT_NE(g.output.find("range.csv:2: cam_y = 1023 is outside"), std::string::npos) << g.output;
}

TEST(CalibrateCli, DegeneratePointsExitTwoWithOneLineAndNothingWritten) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "points.csv") << "cam_x,cam_y,screen_x,screen_y\n0,0,0,0\n100,100,0.5,0.5\n200,200,1,1\n0,700,0,1\n";
  const auto cal = dir / "cal.toml";
  const test::CliResult r =
      test::run_mallet("calibrate fit --points " + (dir / "points.csv").string() + " --out " + cal.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("points 1, 2 and 3 are (nearly) on one line"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(std::filesystem::exists(cal));

  std::ofstream(dir / "three.csv") << "cam_x,cam_y,screen_x,screen_y\n0,0,0,0\n100,0,1,0\n0,100,0,1\n";
  const test::CliResult t =
      test::run_mallet("calibrate fit --points " + (dir / "three.csv").string() + " --out " + cal.string());
  EXPECT_EQ(t.status, 2);
  EXPECT_NE(t.output.find("at least 4 points, got 3"), std::string::npos) << t.output;
  EXPECT_FALSE(std::filesystem::exists(cal));
}

TEST(CalibrateCli, MapWithABadCalibrationExitsTwoNamingTheLine) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "cal.toml") << "format_version = 1\n[camera_to_screen]\nmatrix = [1, 2]\n";
  const test::CliResult r = test::run_mallet("calibrate map --calibration " + (dir / "cal.toml").string() + " 1 2");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("cal.toml:3:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("camera_to_screen.matrix: expected 9 numbers"), std::string::npos) << r.output;

  const test::CliResult missing = test::run_mallet("calibrate map --calibration " + (dir / "none.toml").string() + " 1 2");
  EXPECT_EQ(missing.status, 2) << missing.output;
  const test::CliResult usage = test::run_mallet("calibrate map 1 2");
  EXPECT_EQ(usage.status, 2) << usage.output;
}

TEST(CalibrateCli, HelpDocumentsBothFormats) {
  const test::CliResult fit = test::run_mallet("calibrate fit --help");
  EXPECT_EQ(fit.status, 0);
  EXPECT_NE(fit.output.find("cam_x,cam_y,screen_x,screen_y"), std::string::npos) << fit.output;
  EXPECT_NE(fit.output.find("[camera_to_screen] matrix"), std::string::npos) << fit.output;
  const test::CliResult map = test::run_mallet("calibrate map --help");
  EXPECT_NE(map.output.find("screen_x screen_y"), std::string::npos) << map.output;
}

}  // namespace
}  // namespace mallet::app
