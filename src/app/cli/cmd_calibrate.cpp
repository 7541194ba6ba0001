// `mallet calibrate fit|map`: the camera → screen homography from a CSV of point pairs, and
// the map it gives. The kiosk's calibration screen uses the same core code
// (fit_homography, write_calibration_file).
#include <charconv>
#include <cmath>
#include <cstdio>

#include "app/cli/commands.hpp"
#include "core/calibration_file.hpp"
#include "core/csv_file.hpp"
#include "core/file_error.hpp"
#include "core/text_lines.hpp"
#include "core/homography.hpp"

namespace mallet::app {

namespace {

struct PointPairs {
  std::vector<Vec2> camera;
  std::vector<Vec2> screen;
  std::vector<std::uint32_t> lines;  //!< the CSV line of each pair
};

using text::parse_double;

// Strict: a header naming the four columns (any order, no others), then one pair per line;
// '#' comments and blank lines are skipped; every problem is FILE:LINE: problem.
PointPairs parse_points_csv(std::string_view text, const std::string& name) {
  static constexpr const char* kColumns[4] = {"cam_x", "cam_y", "screen_x", "screen_y"};
  constexpr std::string_view kHint = "the header must be cam_x,cam_y,screen_x,screen_y";
  const csv::Table table = csv::parse(text, name, {.hand_written = true});
  if (!table.has_header())
    throw FileError(name, 0, 0, "empty file (expected the header cam_x,cam_y,screen_x,screen_y and rows)");
  for (std::size_t i = 0; i < table.header.size(); ++i) {
    const std::string& h = table.header[i];
    if (std::find(std::begin(kColumns), std::end(kColumns), h) == std::end(kColumns))
      table.fail(table.header_line, "unknown column \"" + h + "\" (" + std::string(kHint) + ")");
    if (table.find(h) != i) table.fail(table.header_line, "column \"" + h + "\" appears twice");
  }
  std::size_t col[4];
  for (int k = 0; k < 4; ++k) col[k] = table.column(kColumns[k], kHint);
  PointPairs out;
  for (const csv::Row& row : table.rows) {
    double v[4];
    for (int k = 0; k < 4; ++k) {
      v[k] = table.number(row, col[k], kColumns[k]);
      if (!std::isfinite(v[k]))
        table.fail(row.line, std::string(kColumns[k]) + ": \"" + row[col[k]] + "\" is not a finite number");
    }
    if (!(v[0] >= 0 && v[0] <= 1023))
      table.fail(row.line, "cam_x = " + row[col[0]] + " is outside the camera's 0..1023 pixels");
    if (!(v[1] >= 0 && v[1] <= 767))
      table.fail(row.line, "cam_y = " + row[col[1]] + " is outside the camera's 0..767 pixels (1023 = an empty IR slot)");
    for (int k = 2; k < 4; ++k)
      if (!(v[k] >= 0 && v[k] <= 1))
        table.fail(row.line, std::string(kColumns[k]) + " = " + row[col[k]] + " is outside the normalised screen 0..1");
    out.camera.push_back({v[0], v[1]});
    out.screen.push_back({v[2], v[3]});
    out.lines.push_back(row.line);
  }
  return out;
}

PointPairs read_points_csv(const std::filesystem::path& path) {
  return parse_points_csv(text::read_file(path), path.string());
}

//! The screen's size in pixels for the errors, "1920x1080" (fractions allowed).
Result<ScreenSize, std::string> parse_screen_size(const std::string& text) {
  const std::size_t x = text.find('x');
  double w = 0, h = 0;
  if (x == std::string::npos || !parse_double(std::string_view(text).substr(0, x), w) ||
      !parse_double(std::string_view(text).substr(x + 1), h) || !(w > 0 && h > 0 && w < 1e6 && h < 1e6))
    return refused("expected WIDTHxHEIGHT in pixels (e.g. 1920x1080), got \"" + text + "\"");
  return ScreenSize{w, h};
}

void add_fit(CLI::App& calibrate) {
  struct Options {
    std::filesystem::path points;
    std::filesystem::path out;
    std::string screen = "1920x1080";
    std::string remote;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = calibrate.add_subcommand("fit", "Fit the camera -> screen homography to point pairs; write CAL");
  cmd->footer(R"(FILE.csv: a header naming the columns cam_x,cam_y,screen_x,screen_y (any order), then one
calibration point per line: cam_x,cam_y = the LED's raw IR camera position in pixels
(x 0..1023, y 0..767, not mirrored, as `mallet wiimote decode` prints it); screen_x,screen_y
= where the target was shown, normalised 0..1 with the origin top-left. Blank lines and
lines starting with # are skipped. At least 4 points, with at least 4 of them having no 3
on one line (e.g. the 4 corners); more points are fitted in least squares.
Prints the 3x3 matrix and each point's reprojection error in screen pixels (--screen) and
camera pixels, then writes CAL atomically (temporary file + rename: a failed write leaves
the old CAL as it was). CAL is TOML:
  format_version = 1, created_utc, created_by, remote (optional)
  [camera_to_screen] matrix = [9 numbers, row-major 3x3 H] with
    [screen_x*w, screen_y*w, w] = H . [cam_x, cam_y, 1]
  screen_width_px, screen_height_px, points, rms_error_screen_px, max_error_screen_px,
  rms_error_camera_px, max_error_camera_px
Bad input (a malformed line: FILE:LINE: problem; degenerate points: one line saying why)
exits 2 with nothing written.)");
  cmd->add_option("--points", o->points, "Calibration points CSV (cam_x,cam_y,screen_x,screen_y)")->required();
  cmd->add_option("--out", o->out, "Calibration file to write (TOML)")->required();
  cmd->add_option("--screen", o->screen, "Screen size WIDTHxHEIGHT in pixels, for the errors")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& value) {
            const Result<ScreenSize, std::string> size = parse_screen_size(value);
            return size ? std::string() : size.error();
          },
          "WIDTHxHEIGHT"));
  cmd->add_option("--remote", o->remote, "Identity of the Wii Remote used (stored in CAL)");
  cmd->callback([o] {
    const ScreenSize screen = parse_screen_size(o->screen).value();  // checked by --screen's validator
    const PointPairs pairs = read_points_csv(o->points);
    const auto result = fit_homography(pairs.camera, pairs.screen, screen);
    if (!result) throw FileError(o->points.string(), 0, 0, result.error());
    const HomographyFit& fit = *result;
    const auto& h = fit.h.h;
    std::printf("camera -> normalised screen (row-major 3x3):\n");
    for (int r = 0; r < 3; ++r) std::printf("  % .10e % .10e % .10e\n", h[r * 3], h[r * 3 + 1], h[r * 3 + 2]);
    std::printf("reprojection error per point (screen %gx%g px; camera px):\n", screen.width_px, screen.height_px);
    std::printf("  %-5s %-5s %10s %10s %10s %10s %10s %10s\n", "point", "line", "cam_x", "cam_y", "screen_x",
                "screen_y", "screen_px", "camera_px");
    for (std::size_t i = 0; i < pairs.camera.size(); ++i)
      std::printf("  %-5zu %-5u %10.3f %10.3f %10.5f %10.5f %10.3f %10.3f\n", i + 1, pairs.lines[i], pairs.camera[i].x,
                  pairs.camera[i].y, pairs.screen[i].x, pairs.screen[i].y, fit.reprojection_error_px[i],
                  fit.camera_error_px[i]);
    std::printf("rms %.3f px, max %.3f px on screen; rms %.3f px, max %.3f px in the camera (%zu points)\n",
                fit.rms_px, fit.max_px, fit.camera_rms_px, fit.camera_max_px, pairs.camera.size());
    const Calibration cal =
        calibration_from_fit(fit, "mallet calibrate fit (from " + o->points.filename().string() + ")", o->remote);
    write_calibration_file(o->out, cal);
    std::printf("wrote %s\n", o->out.string().c_str());
  });
}

void add_map(CLI::App& calibrate) {
  struct Options {
    std::filesystem::path calibration;
    double cam_x = 0;
    double cam_y = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = calibrate.add_subcommand("map", "Map one camera point to the screen through a calibration");
  cmd->footer(R"(Prints `screen_x screen_y` on one line, separated by a space, normalised 0..1 with the
origin top-left (values outside 0..1 are off screen), with 17 significant digits so that
they read back as the same doubles. CAM_X CAM_Y are raw IR camera pixels.
CAL is the file `mallet calibrate fit` writes (see `mallet calibrate fit --help`).
A bad CAL (FILE:LINE:COLUMN: key: problem) or a point the map sends to infinity exits 2.)");
  cmd->add_option("--calibration", o->calibration, "Calibration file (from `mallet calibrate fit`)")->required();
  cmd->add_option("CAM_X", o->cam_x, "Camera x (pixels)")->required();
  cmd->add_option("CAM_Y", o->cam_y, "Camera y (pixels)")->required();
  cmd->callback([o] {
    const Calibration cal = load_calibration(o->calibration);
    if (!std::isfinite(o->cam_x) || !std::isfinite(o->cam_y))
      throw FileError("CAM_X CAM_Y", 0, 0, "must be finite numbers");
    const std::optional<Vec2> s = cal.camera_to_screen.try_map({o->cam_x, o->cam_y});
    if (!s) throw FileError("CAM_X CAM_Y", 0, 0, "this camera point is on the calibration's vanishing line (no screen point)");
    std::printf("%.17g %.17g\n", s->x, s->y);
  });
}

}  // namespace

void register_calibrate(CLI::App& app) {
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Calibrations: the Wii Remote's camera -> screen, the actuator through the sound card");
  calibrate->require_subcommand(1);
  calibrate->footer(R"(fit: point pairs (CSV) -> camera calibration file; map: one camera point -> screen through it.
actuator: the actuator and stick measured with a sweep, their bounded inverse saved (--verify:
Table 1's strikes as felt); latency: the sound card's output latency on a loopback cable.
Run `mallet calibrate COMMAND --help` for each one's files.)");
  add_fit(*calibrate);
  add_map(*calibrate);
  add_calibrate_actuator(*calibrate);
  add_calibrate_latency(*calibrate);
}

}  // namespace mallet::app
