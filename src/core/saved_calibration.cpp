#include "core/saved_calibration.hpp"

#include <cstdio>
#include <exception>
#include <system_error>

#include <fmt/format.h>

#include "core/atomic_file.hpp"

namespace mallet {

SavedCalibration load_saved_calibration(const std::filesystem::path& file) {
  SavedCalibration out;
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    out.status = "calibration: none yet";
    return out;
  }
  try {
    out.calibration = load_calibration(file);
    out.status = fmt::format("calibration: {} ({}, max error {:.1f} px)", file.string(),
                             out.calibration->created_utc, out.calibration->max_error_screen_px);
  } catch (const std::exception& e) {  // FileError, and whatever else reading it throws
    const std::optional<std::filesystem::path> bad = set_aside_as_bad(file);
    const std::string kept = bad ? "kept as " + bad->string() : "left in place (it could not be moved)";
    out.warning = std::string(e.what()) + "; the file is " + kept + "; calibrating again";
    out.status = "calibration: the saved one was unusable, " + kept + ": calibrate again";
  }
  return out;
}

}  // namespace mallet
