#pragma once
// Where a camera's frames come from, behind a small interface: the V4L2 capture
// (v4l2_grabber: open, negotiate, mmap streaming, the kernel's stamps) for the kiosk, and a
// recorded or generated stream for tests, so that the reading thread (camera_device), its
// reconnection and its tracking are tested without a camera.
#include <string>
#include <vector>

#include "core/result.hpp"
#include "input/camera/camera_frame.hpp"

namespace mallet::input::camera {

//! What a camera agreed to when it was opened: the kiosk logs it, `camera monitor` and the
//! doctor show it.
struct CameraMode {
  std::string device;    //!< the node opened, e.g. /dev/video0
  std::string name;      //!< the camera's own name (V4L2 card), e.g. "USB 2.0 Camera"
  std::string driver;    //!< e.g. uvcvideo
  int width = 0;
  int height = 0;
  PixelFormat format = PixelFormat::grey;
  double rate_hz = 0;    //!< the frame interval the driver agreed to (0: it would not say)
  int exposure_us = 0;   //!< the exposure in force (0: automatic, or no such control)
  bool exposure_manual = false;
  int gain = -1;         //!< the gain in force (-1: no gain control)
  //! How a frame's time is found: the kernel's stamp at the start or the end of the
  //! exposure moved to its middle, or (a driver without monotonic stamps) the time it was read.
  std::string stamping;
  std::vector<std::string> notes;  //!< what was asked and not given, one sentence each
};

//! Why there is no frame: the device went away (unplugged: reopen), or something else that
//! a reopen may cure.
struct GrabError {
  std::string message;
  bool gone = false;  //!< ENODEV and the like: the camera is no longer there
};

class FrameGrabber {
 public:
  virtual ~FrameGrabber() = default;
  //! Opens the camera and starts streaming. One line a person can act on when it cannot.
  virtual Result<CameraMode, std::string> open() = 0;
  //! Waits up to `timeout_ms` for the next frame; true with `frame` set, false on a
  //! timeout (or a wake()). The frame's bytes stay valid until the next call or close().
  virtual Result<bool, GrabError> next(int timeout_ms, CameraFrame& frame) = 0;
  //! Stops streaming and closes; open() may follow.
  virtual void close() = 0;
  //! Ends a next() that is waiting, from another thread.
  virtual void wake() = 0;
  //! How the frames are stamped (CameraMode::stamping), known once a frame came; empty before.
  virtual std::string stamping() const = 0;
};

}  // namespace mallet::input::camera
