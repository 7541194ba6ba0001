#pragma once
// The calibration the kiosk saved, read at start-up. A missing file means "calibrate"; an
// unusable one (corrupt, truncated by hand, from another version) is kept for the operator
// as calibration.toml.bad, said in the log and on the operator page, and the kiosk goes on
// as if it had none: its calibration screen comes up and saves a good one.
#include <filesystem>
#include <optional>
#include <string>

#include "core/calibration_file.hpp"

namespace mallet {

struct SavedCalibration {
  std::optional<Calibration> calibration;  //!< nothing: calibrate
  std::string status;                      //!< the operator page's line ("calibration: …")
  std::string warning;                     //!< for the log when the file was unusable, else empty
};

SavedCalibration load_saved_calibration(const std::filesystem::path& file);

}  // namespace mallet
