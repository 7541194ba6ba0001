#pragma once
// The camera → screen calibration the kiosk loads at start-up: a small TOML file written
// by `mallet calibrate fit` (and by the kiosk's calibration screen), e.g.
//
//   # Mallet camera → screen calibration.
//   # Written by mallet calibrate fit (from points.csv) at 2025-05-01T09:30:00Z.
//   # ...
//   format_version = 1
//   created_utc = "2025-05-01T09:30:00Z"
//   created_by = "mallet calibrate fit (from points.csv)"
//   remote = "00:1f:32:aa:bb:cc"          # optional: the Wii Remote it was made with
//   ir_sensitivity = "wii1"               # optional: the IR camera sensitivity the kiosk's
//                                         # calibration screen chose (a kSensitivityPresets name)
//
//   [camera_to_screen]
//   matrix = [ 1.2e-03, 0.0, -0.1,       # row-major 3×3 H:
//              0.0, 1.5e-03, -0.2,       # [sx·w, sy·w, w] = H · [cam_x, cam_y, 1]
//              0.0, 0.0, 1.0 ]
//   screen_width_px = 1920                # the screen the errors below are measured on
//   screen_height_px = 1080
//   points = 9
//   rms_error_screen_px = 0.8
//   max_error_screen_px = 1.4
//   rms_error_camera_px = 0.5
//   max_error_camera_px = 0.9
//
// cam_x, cam_y are raw IR camera pixels (0..1023, 0..767, not mirrored); sx, sy are
// normalised screen coordinates (0..1, origin top-left).
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/homography.hpp"

namespace mallet {

struct Calibration {
  Homography camera_to_screen;  //!< raw camera pixels → normalised screen
  ScreenSize screen;            //!< the screen it was fitted for
  std::int64_t points = 0;      //!< number of calibration points used
  double rms_error_screen_px = 0.0;
  double max_error_screen_px = 0.0;
  double rms_error_camera_px = 0.0;
  double max_error_camera_px = 0.0;
  std::string remote;      //!< the Wii Remote's identity (e.g. its address); empty = unknown
  std::string ir_sensitivity;  //!< the camera sensitivity chosen with it; empty = the configured one
  std::string created_utc; //!< ISO 8601, e.g. 2025-05-01T09:30:00Z
  std::string created_by;  //!< what made it, e.g. "mallet calibrate fit (from points.csv)"
};

//! A calibration from a fit, stamped with the current UTC time.
Calibration calibration_from_fit(const HomographyFit& fit, std::string created_by, std::string remote = {});

//! The current time as ISO 8601 UTC ("2025-05-01T09:30:00Z").
std::string utc_timestamp_now();

//! Loads a calibration file; every problem is a FileError naming file:line:column and key
//! (unknown keys refused; the matrix must be 9 finite numbers and invertible).
Calibration load_calibration(const std::filesystem::path& path);
Calibration parse_calibration(std::string_view text, const std::string& name);

//! The file's text (with the comment header saying what made it and when). Numbers are
//! written with 17 significant digits, so a load gives back the same doubles.
std::string format_calibration(const Calibration& calibration);

//! Writes the file atomically: a temporary file in the same folder, fsync, rename over the
//! target, fsync of the folder. On any failure the old file (if any) is left as it was, the
//! temporary file is removed, and std::runtime_error names the path and the reason.
//! Refuses (std::invalid_argument, nothing written) a calibration that would not load.
void write_calibration_file(const std::filesystem::path& path, const Calibration& calibration);

}  // namespace mallet
