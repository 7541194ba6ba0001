// Camera → screen calibration: the normalised DLT recovers a known homography exactly,
// stays bounded under camera noise, refuses degenerate point sets with a reason, and the
// calibration file round-trips, is written atomically and reports bad lines.
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <sys/resource.h>

#include "core/calibration_file.hpp"
#include "core/file_error.hpp"
#include "core/homography.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const ScreenSize kScreen{1920, 1080};

std::array<double, 9> mul(const std::array<double, 9>& a, const std::array<double, 9>& b) {
  std::array<double, 9> c{};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) c[r * 3 + j] += a[r * 3 + k] * b[k * 3 + j];
  return c;
}

// A camera → normalised screen map built from parts (so it is known without fitting):
// camera pixels → unit square, optional mirror in x, perspective (px, py), rotation,
// scale, translation.
Homography make_truth(double px, double py, double angle, double scale, double tx, double ty, bool mirror) {
  std::array<double, 9> m{1.0 / 1024, 0, 0, 0, 1.0 / 768, 0, 0, 0, 1};
  if (mirror) m = mul({-1, 0, 1, 0, 1, 0, 0, 0, 1}, m);
  // Perspective that keeps the unit square's centre in place: w = 1 + px (x − ½) + py (y − ½).
  m = mul({1, 0, 0, 0, 1, 0, px, py, 1 - (px + py) / 2}, m);
  const double c = std::cos(angle) * scale, s = std::sin(angle) * scale;
  m = mul({c, -s, tx, s, c, ty, 0, 0, 1}, m);
  return Homography{m};
}

Homography random_truth(std::mt19937& rng, bool mirror) {
  std::uniform_real_distribution<double> persp(-0.8, 0.8), angle(-0.3, 0.3), scale(0.8, 1.25), shift(-0.1, 0.1);
  return make_truth(persp(rng), persp(rng), angle(rng), scale(rng), shift(rng), shift(rng), mirror);
}

std::vector<Vec2> map_all(const Homography& h, const std::vector<Vec2>& pts) {
  std::vector<Vec2> out;
  for (Vec2 p : pts) out.push_back(h.map(p));
  return out;
}

// Largest distance, in screen pixels, between two maps over the whole camera image.
double max_screen_gap_px(const Homography& a, const Homography& b) {
  double worst = 0;
  for (int i = 0; i <= 32; ++i)
    for (int j = 0; j <= 24; ++j) {
      const Vec2 c{1023.0 * i / 32, 767.0 * j / 24};
      const Vec2 p = a.map(c), q = b.map(c);
      worst = std::max(worst, std::hypot((p.x - q.x) * kScreen.width_px, (p.y - q.y) * kScreen.height_px));
    }
  return worst;
}

HomographyFit fit_of(const Result<HomographyFit, std::string>& r) {
  if (!r) ADD_FAILURE() << "refused: " << r.error();
  return r.value_or(HomographyFit{});
}

std::string reason_of(const std::vector<Vec2>& from, const std::vector<Vec2>& to) {
  const auto r = fit_homography(from, to, kScreen);
  if (!r) return r.error();
  ADD_FAILURE() << "accepted a degenerate set";
  return {};
}

const std::vector<Vec2> kCorners{{100, 80}, {900, 100}, {950, 700}, {60, 680}};

TEST(Homography, FourPointsRecoverRandomMapsExactly) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const Homography truth = random_truth(rng, trial % 2 == 1);
    const std::vector<Vec2> cam = kCorners;
    const HomographyFit fit = fit_of(fit_homography(cam, map_all(truth, cam), kScreen));
    EXPECT_LT(max_screen_gap_px(fit.h, truth), 1e-6) << "trial " << trial;
    EXPECT_LT(fit.max_px, 1e-8);
    EXPECT_LT(fit.camera_max_px, 1e-8);
    ASSERT_EQ(fit.reprojection_error_px.size(), 4u);
    // Same matrix up to scale (the fit is scaled to h33 = 1).
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(fit.h.h[k], truth.h[k] / truth.h[8], 1e-9 * std::abs(truth.h[0] / truth.h[8]));
  }
}

TEST(Homography, StrongPerspectiveAndMirrorInX) {
  const Homography truth = make_truth(0.9, -0.6, 0.2, 1.0, 0.0, 0.0, true);
  // w (the perspective divisor) varies more than 3× between the corners of the camera image.
  double w_min = 1e300, w_max = 0;
  for (Vec2 c : {Vec2{0, 0}, Vec2{1023, 0}, Vec2{0, 767}, Vec2{1023, 767}}) {
    const double w = std::abs(truth.h[6] * c.x + truth.h[7] * c.y + truth.h[8]);
    w_min = std::min(w_min, w), w_max = std::max(w_max, w);
  }
  EXPECT_GT(w_max / w_min, 3.0);
  const std::vector<Vec2> cam = kCorners;
  const HomographyFit fit = fit_of(fit_homography(cam, map_all(truth, cam), kScreen));
  EXPECT_LT(max_screen_gap_px(fit.h, truth), 1e-6);
  // Mirrored: the camera's left edge lands right of its right edge on the screen.
  EXPECT_GT(fit.h.map({0, 384}).x, fit.h.map({1023, 384}).x);
}

TEST(Homography, NinePointsLeastSquaresRecoverExactData) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 100; ++trial) {
    const Homography truth = random_truth(rng, trial % 3 == 0);
    std::vector<Vec2> cam;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) cam.push_back({150.0 + 350.0 * i, 120.0 + 260.0 * j});
    const HomographyFit fit = fit_of(fit_homography(cam, map_all(truth, cam), kScreen));
    EXPECT_LT(max_screen_gap_px(fit.h, truth), 1e-6) << "trial " << trial;
    EXPECT_LT(fit.rms_px, 1e-8);
    EXPECT_EQ(fit.reprojection_error_px.size(), 9u);
  }
}

// ±1 camera pixel of uniform noise on every point (the Wii camera's own resolution), for a
// camera that sees the screen at about 970×660 camera pixels (≈2 screen px per camera px),
// with perspective and a mirror. Measured (seed 7, 500 trials each), largest error anywhere
// on the 1920×1080 screen: 4 corner points 3.78 px worst, 2.30 px mean of the per-trial
// maxima; a 3×3 grid 3.44 px worst, 1.73 px mean. The bounds below leave ≈30–40 % margin.
struct NoiseResult {
  double worst_px = 0;
  double mean_of_max_px = 0;
};

NoiseResult noisy_fits(const std::vector<Vec2>& screen_targets, int trials) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  // Screen seen from the remote with some perspective and a mirror.
  const Homography truth = make_truth(0.3, -0.2, 0.05, 1.2, -0.1, -0.1, true);
  const Homography screen_to_cam = *truth.inverse();
  NoiseResult r;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<Vec2> cam;
    for (Vec2 s : screen_targets) {
      const Vec2 c = screen_to_cam.map(s);
      cam.push_back({c.x + noise(rng), c.y + noise(rng)});
    }
    const HomographyFit fit = fit_of(fit_homography(cam, screen_targets, kScreen));
    double worst = 0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const Vec2 s{i / 20.0, j / 20.0};
        const Vec2 back = fit.h.map(screen_to_cam.map(s));
        worst = std::max(worst, std::hypot((back.x - s.x) * kScreen.width_px, (back.y - s.y) * kScreen.height_px));
      }
    r.worst_px = std::max(r.worst_px, worst);
    r.mean_of_max_px += worst / trials;
  }
  return r;
}

TEST(Homography, OneCameraPixelOfNoiseGivesBoundedScreenError) {
  const std::vector<Vec2> corners{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<Vec2> grid;
  for (double x : {0.0, 0.5, 1.0})
    for (double y : {0.0, 0.5, 1.0}) grid.push_back({x, y});
  const Homography truth = make_truth(0.3, -0.2, 0.05, 1.2, -0.1, -0.1, true);
  const Homography s2c = *truth.inverse();
  const Vec2 tl = s2c.map({0, 0}), br = s2c.map({1, 1});
  std::printf("screen spans about %.0f x %.0f camera px\n", std::abs(br.x - tl.x), std::abs(br.y - tl.y));
  const NoiseResult four = noisy_fits(corners, 500);
  const NoiseResult nine = noisy_fits(grid, 500);
  std::printf("±1 camera px noise, error over the whole screen (1920x1080 px): 4 corners worst %.2f px "
              "(mean of maxima %.2f); 3x3 grid worst %.2f px (mean of maxima %.2f)\n",
              four.worst_px, four.mean_of_max_px, nine.worst_px, nine.mean_of_max_px);
  EXPECT_LT(four.worst_px, 5.0);
  EXPECT_LT(four.mean_of_max_px, 3.0);
  EXPECT_LT(nine.worst_px, 4.5);
  EXPECT_LT(nine.mean_of_max_px, 2.3);
  EXPECT_LT(nine.mean_of_max_px, four.mean_of_max_px) << "more points must help";
}

TEST(Homography, ReprojectionErrorIsReportedInScreenAndCameraPixels) {
  // 4 corners exact plus a centre point displaced by exactly 10 screen px in x.
  const Homography truth = make_truth(0.2, 0.1, 0.0, 1.0, 0.0, 0.0, false);
  std::vector<Vec2> cam = kCorners;
  cam.push_back({500, 390});
  std::vector<Vec2> screen = map_all(truth, cam);
  screen[4].x += 10.0 / kScreen.width_px;
  const HomographyFit fit = fit_of(fit_homography(cam, screen, kScreen));
  ASSERT_EQ(fit.reprojection_error_px.size(), 5u);
  EXPECT_GT(fit.max_px, 3.0);
  EXPECT_LT(fit.max_px, 10.0);  // least squares spreads the outlier
  EXPECT_GT(fit.camera_max_px, 0.5);
  double sum = 0;
  for (double e : fit.reprojection_error_px) sum += e * e;
  EXPECT_NEAR(fit.rms_px, std::sqrt(sum / 5), 1e-12);
  EXPECT_EQ(fit.screen, kScreen);
}

TEST(Homography, RefusesFewerThanFourPoints) {
  const std::vector<Vec2> three(kCorners.begin(), kCorners.begin() + 3);
  EXPECT_NE(reason_of(three, three).find("at least 4 points, got 3"), std::string::npos);
  EXPECT_NE(reason_of({}, {}).find("got 0"), std::string::npos);
  EXPECT_NE(reason_of(kCorners, three).find("4 camera points but 3 screen"), std::string::npos);
}

TEST(Homography, RefusesCollinearPoints) {
  const std::vector<Vec2> screen{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  // Exactly collinear in the camera: points 1, 2, 3.
  std::string r = reason_of({{0, 0}, {500, 0}, {1000, 0}, {0, 700}}, screen);
  EXPECT_NE(r.find("points 1, 2 and 3"), std::string::npos) << r;
  EXPECT_NE(r.find("camera"), std::string::npos) << r;
  // Nearly collinear: 3 px off a 1000 px line (0.3 %).
  r = reason_of({{0, 0}, {500, 3}, {1000, 0}, {0, 700}}, screen);
  EXPECT_NE(r.find("on one line"), std::string::npos) << r;
  // Collinear on the screen side.
  r = reason_of(kCorners, {{0, 0}, {0.5, 0.5}, {1, 1}, {0, 1}});
  EXPECT_NE(r.find("screen"), std::string::npos) << r;
  // Many points, all on one line, and all but one on a line.
  std::vector<Vec2> line_cam, line_screen;
  for (int i = 0; i < 8; ++i) line_cam.push_back({100.0 + 100 * i, 50.0 + 80 * i}), line_screen.push_back({i / 7.0, i / 7.0});
  r = reason_of(line_cam, line_screen);
  EXPECT_NE(r.find("general position"), std::string::npos) << r;
  line_cam.push_back({900, 100});
  line_screen.push_back({1, 0});
  r = reason_of(line_cam, line_screen);
  EXPECT_NE(r.find("general position"), std::string::npos) << r;
}

TEST(Homography, RefusesRepeatedPoints) {
  std::vector<Vec2> cam = kCorners, screen{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  cam.push_back(cam[1]);
  screen.push_back({0.5, 0.5});
  std::string r = reason_of(cam, screen);
  EXPECT_NE(r.find("points 2 and 5 repeat the same camera point"), std::string::npos) << r;
  cam.back() = {500, 400};
  screen.back() = screen[2];
  r = reason_of(cam, screen);
  EXPECT_NE(r.find("points 3 and 5 repeat the same screen point"), std::string::npos) << r;
}

TEST(Homography, RefusesNonFiniteCoordinates) {
  const std::vector<Vec2> screen{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (double bad : {kNaN, kInf, -kInf}) {
    std::vector<Vec2> cam = kCorners;
    cam[2].y = bad;
    EXPECT_NE(reason_of(cam, screen).find("point 3: the camera coordinates are not finite"), std::string::npos);
    std::vector<Vec2> s = screen;
    s[0].x = bad;
    EXPECT_NE(reason_of(kCorners, s).find("point 1: the screen coordinates are not finite"), std::string::npos);
  }
}

TEST(Homography, RefusesAFitThatFoldsTheScreen) {
  // Two corners swapped: no orientation-consistent map exists (a bow tie).
  const std::string r = reason_of(kCorners, {{0, 0}, {1, 0}, {0, 1}, {1, 1}});
  EXPECT_NE(r.find("wrong order"), std::string::npos) << r;
}

TEST(Homography, InverseRoundTrips) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Homography h = random_truth(rng, trial % 2 == 0);
    const std::optional<Homography> inv = h.inverse();
    ASSERT_TRUE(inv);
    for (Vec2 c : {Vec2{0, 0}, Vec2{1023, 767}, Vec2{512, 384}, Vec2{17.5, 700.25}}) {
      const Vec2 back = inv->map(h.map(c));
      EXPECT_NEAR(back.x, c.x, 1e-9);
      EXPECT_NEAR(back.y, c.y, 1e-9);
    }
    const std::optional<Homography> twice = inv->inverse();
    ASSERT_TRUE(twice);
    EXPECT_LT(max_screen_gap_px(*twice, h), 1e-7);
  }
  EXPECT_FALSE((Homography{{1, 2, 3, 2, 4, 6, 0, 0, 1}}.inverse()));  // singular
  EXPECT_FALSE((Homography{{1, 0, 0, 0, 1, 0, 0, 0, kNaN}}.inverse()));
}

TEST(Homography, APointOnTheVanishingLineHasNoImage) {
  const Homography h{{1, 0, 0, 0, 1, 0, 0.01, 0, -1}};  // w = 0 at x = 100
  EXPECT_FALSE(h.try_map({100, 5}));
  EXPECT_TRUE(std::isnan(h.map({100, 5}).x));
  EXPECT_TRUE(h.try_map({50, 5}));
  EXPECT_FALSE(h.try_map({kNaN, 5}));
}

// ---- the calibration file ------------------------------------------------------------

Calibration sample_calibration() {
  const Homography truth = make_truth(0.4, -0.3, 0.1, 1.1, 0.02, -0.03, true);
  std::vector<Vec2> cam = kCorners;
  cam.push_back({500, 390});
  std::vector<Vec2> screen = map_all(truth, cam);
  screen[4].y += 0.003;  // some error to record
  const HomographyFit fit = fit_of(fit_homography(cam, screen, kScreen));
  return calibration_from_fit(fit, "homography_test \"quoted\"", "00:1f:32:aa:bb:cc");
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

using test::file_error_of;

TEST(CalibrationFile, WriteThenLoadGivesTheSameCalibration) {
  const auto dir = test::scratch_dir();
  const Calibration c = sample_calibration();
  write_calibration_file(dir / "cal.toml", c);
  const Calibration back = load_calibration(dir / "cal.toml");
  EXPECT_EQ(back.camera_to_screen.h, c.camera_to_screen.h);  // bit for bit
  EXPECT_EQ(back.screen, c.screen);
  EXPECT_EQ(back.points, 5);
  EXPECT_EQ(back.rms_error_screen_px, c.rms_error_screen_px);
  EXPECT_EQ(back.max_error_screen_px, c.max_error_screen_px);
  EXPECT_EQ(back.rms_error_camera_px, c.rms_error_camera_px);
  EXPECT_EQ(back.max_error_camera_px, c.max_error_camera_px);
  EXPECT_EQ(back.remote, "00:1f:32:aa:bb:cc");
  EXPECT_EQ(back.created_by, c.created_by);
  EXPECT_EQ(back.created_utc, c.created_utc);
  EXPECT_EQ(back.created_utc.size(), 20u) << back.created_utc;  // 2025-05-01T09:30:00Z
  const std::string text = read_text(dir / "cal.toml");
  EXPECT_NE(text.find("# Written by homography_test"), std::string::npos) << text;
  EXPECT_NE(text.find(c.created_utc), std::string::npos);
  // Nothing else left in the folder (the temporary file was renamed).
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

// "{:.17g}" writes a whole error without a point, so TOML reads it back as an integer; one
// beyond 2^53 must still come back as the same double (the fuzzer found it read back as 0).
TEST(CalibrationFile, ErrorsBeyondTwoToThe53RoundTripThroughTheirIntegerForm) {
  Calibration c = sample_calibration();
  c.rms_error_camera_px = 10362658707436286.0;  // even, so exact; 2^53 = 9007199254740992
  c.max_error_camera_px = 9007199254741000.0;
  c.max_error_screen_px = 68115169.0;
  const std::string text = format_calibration(c);
  EXPECT_NE(text.find("rms_error_camera_px = 10362658707436286 "), std::string::npos) << text;
  const Calibration back = parse_calibration(text, "c.toml");
  EXPECT_EQ(back.rms_error_camera_px, c.rms_error_camera_px);
  EXPECT_EQ(back.max_error_camera_px, c.max_error_camera_px);
  EXPECT_EQ(back.max_error_screen_px, c.max_error_screen_px);
}

TEST(CalibrationFile, RemoteIsOptional) {
  Calibration c = sample_calibration();
  c.remote.clear();
  const std::string text = format_calibration(c);
  EXPECT_EQ(text.find("remote ="), std::string::npos);
  EXPECT_EQ(parse_calibration(text, "c.toml").remote, "");
}

TEST(CalibrationFile, AFailedWriteLeavesTheOldFile) {
  const auto dir = test::scratch_dir();
  const auto path = dir / "cal.toml";
  write_calibration_file(path, sample_calibration());
  const std::string old = read_text(path);

  // 1. A write that fails half way: the file size limit stops it after 64 bytes.
  Calibration other = sample_calibration();
  other.remote = "another remote";
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = saved;
  small.rlim_cur = 64;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string message;
  try {
    write_calibration_file(path, other);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(message.find("write failed"), std::string::npos) << message;
  EXPECT_EQ(read_text(path), old);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1) << "temporary file removed";

  // 2. A calibration that would not load is refused before anything is written.
  Calibration broken = sample_calibration();
  broken.camera_to_screen.h[4] = kNaN;
  EXPECT_THROW(write_calibration_file(path, broken), std::invalid_argument);
  broken = sample_calibration();
  broken.camera_to_screen.h = {1, 2, 3, 2, 4, 6, 0, 0, 1};
  EXPECT_THROW(write_calibration_file(path, broken), std::invalid_argument);
  EXPECT_EQ(read_text(path), old);

  // 3. A folder that does not exist.
  EXPECT_THROW(write_calibration_file(dir / "missing" / "cal.toml", other), std::runtime_error);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);

  // And a good write replaces it.
  write_calibration_file(path, other);
  EXPECT_EQ(load_calibration(path).remote, "another remote");
}

const char* kGoodCalibration = R"(format_version = 1
created_utc = "2025-05-01T09:30:00Z"
created_by = "hand"

[camera_to_screen]
matrix = [
  0.001, 0, -0.1,
  0, 0.0013, -0.1,
  0, 0, 1,
]
screen_width_px = 1920
screen_height_px = 1080
points = 4
rms_error_screen_px = 0
max_error_screen_px = 0
rms_error_camera_px = 0
max_error_camera_px = 0
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(CalibrationFile, MalformedFilesNameFileLineAndKey) {
  const Calibration ok = parse_calibration(kGoodCalibration, "c.toml");
  EXPECT_NEAR(ok.camera_to_screen.map({100, 0}).x, 0.0, 1e-15);

  struct Case {
    std::string text;
    std::uint32_t line;
    std::string says;
  };
  const Case cases[] = {
      {replaced(kGoodCalibration, "points = 4", "points = "), 13, ""},  // syntax
      {replaced(kGoodCalibration, "points = 4", "points = 3"), 13, "camera_to_screen.points: must be >= 4"},
      {replaced(kGoodCalibration, "points = 4", "points = 4.5"), 13, "camera_to_screen.points: expected an integer"},
      {replaced(kGoodCalibration, "  0, 0, 1,\n", ""), 6, "camera_to_screen.matrix: expected 9 numbers"},
      {replaced(kGoodCalibration, "  0, 0, 1,\n", "  0, 0, nan,\n"), 9, "camera_to_screen.matrix: expected a finite number"},
      {replaced(kGoodCalibration, "0.001, 0, -0.1,", "0, 0, 0,"), 6, "camera_to_screen.matrix: is singular"},
      {replaced(kGoodCalibration, "screen_height_px = 1080", "screen_height_px = -1"), 12,
       "camera_to_screen.screen_height_px: must be > 0"},
      {replaced(kGoodCalibration, "max_error_camera_px = 0", "max_error_camera_px = \"big\""), 17,
       "camera_to_screen.max_error_camera_px: expected a number"},
      {replaced(kGoodCalibration, "rms_error_screen_px = 0\n", ""), 5, "camera_to_screen.rms_error_screen_px: missing"},
      {replaced(kGoodCalibration, "created_by = \"hand\"", "created_by = \"hand\"\nremote_id = \"x\""), 4, "remote_id: unknown key"},
      {replaced(kGoodCalibration, "format_version = 1", "format_version = 2"), 1, "format_version = 1, got 2"},
  };
  for (const Case& c : cases) {
    const FileError e = file_error_of([&] { parse_calibration(c.text, "c.toml"); });
    EXPECT_EQ(e.file(), "c.toml");
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
  }
  const auto dir = test::scratch_dir();
  const FileError missing = file_error_of([&] { load_calibration(dir / "none.toml"); });
  EXPECT_NE(std::string(missing.what()).find("none.toml: file not found"), std::string::npos) << missing.what();
  std::ofstream(dir / "bad.toml") << replaced(kGoodCalibration, "points = 4", "points = 2");
  const FileError bad = file_error_of([&] { load_calibration(dir / "bad.toml"); });
  EXPECT_EQ(std::string(bad.what()).rfind((dir / "bad.toml").string() + ":13:", 0), 0u) << bad.what();
}

TEST(CalibrationFile, TheSensitivityChosenWithItIsKeptAndCheckedIfThere) {
  Calibration c = sample_calibration();
  EXPECT_EQ(format_calibration(c).find("ir_sensitivity"), std::string::npos);  // none chosen: not written
  EXPECT_EQ(parse_calibration(format_calibration(c), "c.toml").ir_sensitivity, "");
  c.ir_sensitivity = "wii1";
  EXPECT_EQ(parse_calibration(format_calibration(c), "c.toml").ir_sensitivity, "wii1");
  const FileError e = file_error_of(
      [&] { parse_calibration(replaced(format_calibration(c), "\"wii1\"", "\"wii9\""), "c.toml"); });
  EXPECT_EQ(e.file(), "c.toml");
  EXPECT_GT(e.line(), 1u);
  EXPECT_NE(std::string(e.what()).find("ir_sensitivity: unknown preset \"wii9\" (known: "), std::string::npos)
      << e.what();
  c.ir_sensitivity = "loud";
  EXPECT_THROW(write_calibration_file(test::scratch_dir() / "c.toml", c), std::invalid_argument);
}

}  // namespace
}  // namespace mallet
