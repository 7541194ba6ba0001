#pragma once
// `mallet camera list` and `mallet camera monitor`: what the operator sees of a V4L2
// camera as the IR tracker, as `wiimote list` / `wiimote monitor` show the remote. The
// device and the clock are injected, so the loop runs against V4L2 in the binary and
// against a stream in tests; output goes to a FILE*.
#include <atomic>
#include <cstdio>
#include <string>

#include "input/camera/camera_device.hpp"
#include "input/camera/v4l2_node.hpp"
#include "input/clock.hpp"

namespace mallet::app {

//! `camera list`'s output: each capture node with its name, driver, bus, formats, sizes,
//! frame rates and controls; or "No camera found" with the hints.
std::string format_camera_list(const input::camera::CameraScan& scan, const std::string& dir);

struct CameraMonitorOptions {
  double seconds = 0;       //!< 0 = until Ctrl+C
  double interval_s = 0.1;  //!< one status line per interval
};

//! The LED's spread over the samples that saw it: on a still LED, its noise.
struct LedSpread {
  std::uint64_t n = 0;
  double mean_x = 0, mean_y = 0, m2_x = 0, m2_y = 0;  //!< Welford's running sums
  void add(double x, double y);
  double rms_x() const;  //!< the standard deviation, px (0 below two samples)
  double rms_y() const;
};

//! Runs `device` (started here, stopped on return) until `seconds` pass or `interrupted`:
//! a status line per interval, tracking changes as they happen, then a summary (mode,
//! achieved rate, dropped frames, the stamping, the LED's spread). Returns 0 if the camera
//! was open at some point, 1 if never (its problem is the last line).
int run_camera_monitor(input::camera::CameraDevice& device, input::Clock& clock, const CameraMonitorOptions& options,
                       const std::atomic<bool>& interrupted, std::FILE* out);

}  // namespace mallet::app
