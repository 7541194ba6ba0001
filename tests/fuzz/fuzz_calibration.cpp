// The calibration file (calibration.toml) on arbitrary text: a calibration the kiosk can
// use, which survives a write/read round trip exactly, or one FileError line naming the file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/calibration_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.toml";
  mallet::Calibration c;
  try {
    c = mallet::parse_calibration(mallet::fuzz::text_of(data, size), name);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  if (!c.camera_to_screen.inverse()) std::abort();
  const mallet::Calibration again = mallet::parse_calibration(mallet::format_calibration(c), "again.toml");
  if (again.camera_to_screen.h != c.camera_to_screen.h) std::abort();
  if (again.screen.width_px != c.screen.width_px || again.screen.height_px != c.screen.height_px) std::abort();
  if (again.points != c.points || again.rms_error_screen_px != c.rms_error_screen_px ||
      again.max_error_screen_px != c.max_error_screen_px || again.rms_error_camera_px != c.rms_error_camera_px ||
      again.max_error_camera_px != c.max_error_camera_px)
    std::abort();
  if (again.remote != c.remote || again.ir_sensitivity != c.ir_sensitivity || again.created_utc != c.created_utc ||
      again.created_by != c.created_by)
    std::abort();
  return 0;
}
