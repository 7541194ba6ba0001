#include "core/calibration_file.hpp"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/config/toml_reader.hpp"
#include "core/ir_camera_settings.hpp"
#include "core/toml_text.hpp"

namespace mallet {

namespace {

constexpr std::int64_t kCalibrationFormatVersion = 1;

// The first problem that would stop the kiosk from using a calibration: {key, message}.
std::optional<std::pair<std::string, std::string>> problem_of(const Calibration& c) {
  for (double v : c.camera_to_screen.h)
    if (!std::isfinite(v)) return std::pair{std::string("matrix"), std::string("must hold 9 finite numbers")};
  if (!c.camera_to_screen.inverse())
    return std::pair{std::string("matrix"), std::string("is singular (not invertible): refit the calibration")};
  if (!(c.screen.width_px > 0 && std::isfinite(c.screen.width_px)))
    return std::pair{std::string("screen_width_px"), std::string("must be > 0")};
  if (!(c.screen.height_px > 0 && std::isfinite(c.screen.height_px)))
    return std::pair{std::string("screen_height_px"), std::string("must be > 0")};
  if (c.points < 4) return std::pair{std::string("points"), std::string("must be >= 4 (a homography needs 4 points)")};
  if (!c.ir_sensitivity.empty() && !find_sensitivity(c.ir_sensitivity))
    return std::pair{std::string("ir_sensitivity"), "unknown preset (known: " + sensitivity_names() + ")"};
  const std::pair<const char*, double> errors[] = {{"rms_error_screen_px", c.rms_error_screen_px},
                                                   {"max_error_screen_px", c.max_error_screen_px},
                                                   {"rms_error_camera_px", c.rms_error_camera_px},
                                                   {"max_error_camera_px", c.max_error_camera_px}};
  for (const auto& [key, v] : errors)
    if (!(v >= 0 && std::isfinite(v))) return std::pair{std::string(key), std::string("must be finite and >= 0")};
  return std::nullopt;
}

using toml_text::exact_number;

}  // namespace

std::string utc_timestamp_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

Calibration calibration_from_fit(const HomographyFit& fit, std::string created_by, std::string remote) {
  Calibration c;
  c.camera_to_screen = fit.h;
  c.screen = fit.screen;
  c.points = static_cast<std::int64_t>(fit.reprojection_error_px.size());
  c.rms_error_screen_px = fit.rms_px;
  c.max_error_screen_px = fit.max_px;
  c.rms_error_camera_px = fit.camera_rms_px;
  c.max_error_camera_px = fit.camera_max_px;
  c.remote = std::move(remote);
  c.created_utc = utc_timestamp_now();
  c.created_by = std::move(created_by);
  return c;
}

namespace {

Calibration read_calibration(const toml::table& root, const std::string& name) {
  config::TableReader top(root, name);
  Calibration c;
  const std::int64_t version = top.integer("format_version");
  if (version != kCalibrationFormatVersion)
    top.fail("format_version", "this mallet reads format_version = " + std::to_string(kCalibrationFormatVersion) + ", got " +
                                   std::to_string(version));
  c.created_utc = top.string_or("created_utc", "");
  c.created_by = top.string_or("created_by", "");
  c.remote = top.string_or("remote", "");
  c.ir_sensitivity = top.string_or("ir_sensitivity", "");
  if (!c.ir_sensitivity.empty() && !find_sensitivity(c.ir_sensitivity))
    top.fail("ir_sensitivity", "unknown preset \"" + c.ir_sensitivity + "\" (known: " + sensitivity_names() + ")");
  config::TableReader t = top.table("camera_to_screen");
  const std::vector<double> m = t.numbers("matrix");
  if (m.size() != 9)
    t.fail("matrix", "expected 9 numbers (a row-major 3x3 matrix), got " + std::to_string(m.size()));
  std::copy(m.begin(), m.end(), c.camera_to_screen.h.begin());
  c.screen.width_px = t.number("screen_width_px");
  c.screen.height_px = t.number("screen_height_px");
  c.points = t.integer("points");
  c.rms_error_screen_px = t.number("rms_error_screen_px");
  c.max_error_screen_px = t.number("max_error_screen_px");
  c.rms_error_camera_px = t.number("rms_error_camera_px");
  c.max_error_camera_px = t.number("max_error_camera_px");
  t.finish();
  top.finish();
  if (const auto p = problem_of(c)) t.fail(p->first, p->second);
  return c;
}

}  // namespace

Calibration parse_calibration(std::string_view text, const std::string& name) {
  return read_calibration(config::parse_text(text, name), name);
}

Calibration load_calibration(const std::filesystem::path& path) {
  return read_calibration(config::parse_file(path), path.string());
}

std::string format_calibration(const Calibration& c) {
  const auto& h = c.camera_to_screen.h;
  std::string out;
  out += "# Mallet camera -> screen calibration.\n";
  out += "# Written by " + toml_text::comment(c.created_by.empty() ? "mallet" : c.created_by) + " at " +
         toml_text::comment(c.created_utc.empty() ? "an unknown time" : c.created_utc) + ".\n";
  out += "# Maps raw Wii Remote IR camera pixels (x 0..1023, y 0..767, not mirrored) to normalised\n"
         "# screen coordinates (0..1, origin top-left): [sx*w, sy*w, w] = matrix . [cam_x, cam_y, 1].\n"
         "# Refit (mallet calibrate fit) whenever the remote or the screen moves.\n";
  out += "format_version = " + std::to_string(kCalibrationFormatVersion) + "\n";
  out += "created_utc = " + toml_text::quoted(c.created_utc) + "\n";
  out += "created_by = " + toml_text::quoted(c.created_by) + "\n";
  if (!c.remote.empty()) out += "remote = " + toml_text::quoted(c.remote) + "  # the Wii Remote it was made with\n";
  if (!c.ir_sensitivity.empty())
    out += "ir_sensitivity = " + toml_text::quoted(c.ir_sensitivity) + "  # the IR camera sensitivity chosen with it\n";
  out += "\n[camera_to_screen]\n";
  out += "# row-major 3x3 homography, camera pixels -> normalised screen\n";
  out += "matrix = [\n";
  for (int r = 0; r < 3; ++r)
    out += "  " + exact_number(h[r * 3]) + ", " + exact_number(h[r * 3 + 1]) + ", " + exact_number(h[r * 3 + 2]) + ",\n";
  out += "]\n";
  out += "screen_width_px = " + exact_number(c.screen.width_px) + "  # the screen the errors are measured on\n";
  out += "screen_height_px = " + exact_number(c.screen.height_px) + "\n";
  out += "points = " + std::to_string(c.points) + "  # calibration points used in the fit\n";
  out += "rms_error_screen_px = " + exact_number(c.rms_error_screen_px) + "  # |H(cam) - screen| in screen pixels\n";
  out += "max_error_screen_px = " + exact_number(c.max_error_screen_px) + "\n";
  out += "rms_error_camera_px = " + exact_number(c.rms_error_camera_px) +
         "  # |inverse(H)(screen) - cam| in camera pixels\n";
  out += "max_error_camera_px = " + exact_number(c.max_error_camera_px) + "\n";
  return out;
}

void write_calibration_file(const std::filesystem::path& path, const Calibration& calibration) {
  if (const auto p = problem_of(calibration))
    throw std::invalid_argument(path.string() + ": refusing to write a calibration whose " + p->first + " " +
                                p->second);
  write_file_atomically(path, format_calibration(calibration));
}

}  // namespace mallet
