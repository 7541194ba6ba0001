#pragma once
// A V4L2 camera's frames by memory-mapped streaming, the only code of the program that
// talks to a camera (ioctl, mmap, poll); it lives in its own library, mallet_v4l2. What
// reads a frame's bytes is device-free (frame_decode, led_finder) and tested on generated
// streams; this part is proven in the system test's VM on the kernel's vivid driver.
//
// open() negotiates what [camera] asks for: the format (grey, else yuyv, else mjpeg: the
// fastest the camera offers), the size, the frame interval, a manual exposure with the
// camera's "lower the frame rate for a longer exposure" switch off (a UVC camera otherwise
// halves its rate in a dim room), and the gain. What it was not given is said in
// CameraMode::notes. Each frame is stamped with the kernel's monotonic stamp moved to
// mid-exposure (frame_stamp.hpp).
#include <array>
#include <cstddef>
#include <string>

#include "core/app_config.hpp"
#include "input/camera/frame_grabber.hpp"
#include "input/camera/frame_stamp.hpp"

namespace mallet::input::camera {

class V4l2Grabber final : public FrameGrabber {
 public:
  //! `config.device` as find_camera() reads it, looked up again at every open() (a camera
  //! plugged back in may be another /dev/videoN).
  explicit V4l2Grabber(CameraConfig config, std::string video_dir = "/dev");
  ~V4l2Grabber() override;
  V4l2Grabber(const V4l2Grabber&) = delete;
  V4l2Grabber& operator=(const V4l2Grabber&) = delete;

  Result<CameraMode, std::string> open() override;
  Result<bool, GrabError> next(int timeout_ms, CameraFrame& frame) override;
  void close() override;
  void wake() override;
  std::string stamping() const override { return mode_.stamping; }

 private:
  Result<CameraMode, std::string> negotiate(const std::string& path);
  void set_controls(CameraMode& mode);
  Result<void, std::string> start_streaming(const std::string& path);
  void requeue();

  static constexpr std::size_t kBuffers = 4;
  const CameraConfig config_;
  const std::string video_dir_;
  int fd_ = -1;
  int wake_fd_ = -1;
  struct Mapping {
    void* start = nullptr;
    std::size_t length = 0;
  };
  std::array<Mapping, kBuffers> buffers_{};
  std::size_t mapped_ = 0;
  int held_ = -1;  //!< the buffer handed out by next(), queued again at the next call
  CameraMode mode_;
  std::size_t bytes_per_line_ = 0;
  Nanos exposure_ns_ = 0;
};

}  // namespace mallet::input::camera
