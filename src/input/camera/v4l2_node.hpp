#pragma once
// What the V4L2 capture and the camera list share: an ioctl that retries on EINTR, the
// pixel formats' four-character codes, and how a camera is found by what the settings say.
// Only src/input/camera/v4l2_*.cpp include this (with <linux/videodev2.h>); it lives in
// mallet_v4l2 beside them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "input/device_errors.hpp"
#include "input/camera/camera_frame.hpp"

namespace mallet::input::camera {

inline constexpr const char* kDefaultVideoDir = "/dev";
//! The device name that means "the first camera list_cameras() finds".
inline constexpr const char* kAutoCamera = "auto";

//! What an open says when another program streams from the camera (EBUSY): the doctor
//! and the monitor, run beside a running kiosk, meet it.
inline constexpr const char* kCameraInUse =
    "in use by another program: the kiosk, if it runs (stop it first: sudo systemctl stop mallet)";

//! ioctl(), again while a signal interrupts it; -1 with errno set on failure.
int xioctl(int fd, unsigned long request, void* arg);

//! GREY, YUYV or MJPG (MJPEG and JPEG both read as mjpeg); nothing for any other code.
std::optional<PixelFormat> pixel_format_of(std::uint32_t fourcc);
std::uint32_t fourcc_of(PixelFormat format);
//! "YUYV", "MJPG", "RGB3", ... (the four characters, for the list).
std::string fourcc_text(std::uint32_t fourcc);

//! One size a format offers, and the frame rates it offers there.
struct CameraSize {
  int width = 0;
  int height = 0;
  std::vector<double> rates_hz;  //!< fastest first; empty when the driver lists none
  bool stepwise = false;         //!< a range, of which width × height is the largest
};
struct CameraFormat {
  std::uint32_t fourcc = 0;
  std::string description;       //!< the driver's words, e.g. "Motion-JPEG"
  std::vector<CameraSize> sizes;
};
//! A video capture node.
struct CameraInfo {
  std::string path;      //!< /dev/video0
  std::string name;      //!< the V4L2 card name
  std::string driver;
  std::string bus;       //!< bus_info, e.g. usb-0000:00:14.0-2
  std::vector<CameraFormat> formats;
  std::vector<std::string> controls;  //!< "exposure 1..5000 (100 µs)", "gain 0..100", ...
};
struct CameraScan {
  std::vector<CameraInfo> cameras;  //!< in node-number order
  int unreadable = 0;
  std::string first_error;  //!< e.g. "/dev/video0: Permission denied (is the user in the 'video' group?)"
};

//! The capture devices among `dir`/video*: nodes with V4L2_CAP_VIDEO_CAPTURE and streaming
//! (a UVC camera's metadata node is skipped). Never an error: what could not be opened is
//! counted.
CameraScan scan_cameras(const std::string& dir = kDefaultVideoDir, bool with_formats = true);

//! The node `device` names: "auto" = the first camera; a path = itself; anything else =
//! the first camera whose name contains it (case-insensitive). One line when none does.
Result<std::string, std::string> find_camera(const std::string& device, const std::string& dir = kDefaultVideoDir);

}  // namespace mallet::input::camera
