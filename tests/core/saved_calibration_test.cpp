// The calibration saved by the kiosk, read at start-up: a good file is used, a missing one
// asks for a calibration, an unusable one is kept as calibration.toml.bad for the operator
// and said in the log and on the operator page, and the kiosk goes on without it.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/saved_calibration.hpp"
#include "core/calibration_file.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

Calibration a_calibration() {
  Calibration c;
  c.camera_to_screen.h = {-1.0 / 1023.0, 0, 1, 0, 1.0 / 767.0, 0, 0, 0, 1};
  c.created_utc = "2026-11-25T10:00:00Z";
  c.max_error_screen_px = 2.5;
  c.points = 9;
  c.screen = {1920, 1080};
  return c;
}

TEST(SavedCalibration, AGoodFileIsUsed) {
  const fs::path file = test::scratch_dir() / "calibration.toml";
  write_calibration_file(file, a_calibration());
  const SavedCalibration saved = load_saved_calibration(file);
  ASSERT_TRUE(saved.calibration);
  EXPECT_EQ(saved.calibration->created_utc, "2026-11-25T10:00:00Z");
  EXPECT_EQ(saved.status, "calibration: " + file.string() + " (2026-11-25T10:00:00Z, max error 2.5 px)");
  EXPECT_TRUE(saved.warning.empty());
}

TEST(SavedCalibration, NoFileAsksForACalibrationQuietly) {
  const SavedCalibration saved = load_saved_calibration(test::scratch_dir() / "calibration.toml");
  EXPECT_FALSE(saved.calibration);
  EXPECT_EQ(saved.status, "calibration: none yet");
  EXPECT_TRUE(saved.warning.empty());
}

TEST(SavedCalibration, ACorruptFileIsKeptAsBadAndTheKioskCalibratesAgain) {
  const fs::path dir = test::scratch_dir();
  const fs::path file = dir / "calibration.toml";
  std::ofstream(file) << "camera_to_screen = [1, 2\n";  // cut short
  const SavedCalibration saved = load_saved_calibration(file);
  EXPECT_FALSE(saved.calibration);
  EXPECT_FALSE(fs::exists(file));
  ASSERT_TRUE(fs::exists(dir / "calibration.toml.bad"));
  EXPECT_EQ(saved.status, "calibration: the saved one was unusable, kept as " + file.string() +
                              ".bad: calibrate again");
  // The log line names the file and the place, then where it went.
  EXPECT_EQ(saved.warning.rfind(file.string() + ":", 0), 0u) << saved.warning;
  EXPECT_NE(saved.warning.find("; the file is kept as " + file.string() + ".bad; calibrating again"),
            std::string::npos)
      << saved.warning;
  // The next start finds no file: it asks for a calibration, without a warning.
  EXPECT_EQ(load_saved_calibration(file).status, "calibration: none yet");
}

}  // namespace
}  // namespace mallet::app
