#pragma once
// One frame as a V4L2 camera delivers it, and its brightness as the LED finder reads it.
// The capture (ioctl, mmap: v4l2_grabber) is kept apart from everything that reads a
// frame's bytes (frame_decode, led_finder), so the latter is tested on generated streams.
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/enum_names.hpp"
#include "core/time.hpp"

namespace mallet::input::camera {

//! The pixel formats Mallet asks a camera for, fastest first: GREY (8-bit luma, what
//! monochrome global-shutter IR cameras send), YUYV (4:2:2; the luma is every other byte)
//! and MJPEG (decoded with libjpeg-turbo: the fallback of webcams that offer nothing else
//! at their full rate).
enum class PixelFormat { grey, yuyv, mjpeg };
inline constexpr EnumNames<PixelFormat, 3> kPixelFormatNames{
    {{PixelFormat::grey, "grey"}, {PixelFormat::yuyv, "yuyv"}, {PixelFormat::mjpeg, "mjpeg"}}};

//! A captured frame. `bytes` stays valid only until the frame is handed back to the driver.
struct CameraFrame {
  Nanos t_ns = 0;              //!< on the program's monotonic clock (the kernel's stamp, corrected)
  std::uint32_t sequence = 0;  //!< the driver's frame counter: a gap = frames dropped
  int width = 0;
  int height = 0;
  PixelFormat format = PixelFormat::grey;
  std::size_t bytes_per_line = 0;  //!< 0 = packed (width × bytes per pixel); unused for mjpeg
  std::span<const std::uint8_t> bytes;
};

//! The frame's luma (0..255), read in place where the format allows it: pixel (x, y) is
//! data[y · row_stride + x · pixel_step].
struct LumaView {
  int width = 0;
  int height = 0;
  const std::uint8_t* data = nullptr;
  std::ptrdiff_t row_stride = 0;
  int pixel_step = 1;
  std::uint8_t at(int x, int y) const { return data[y * row_stride + static_cast<std::ptrdiff_t>(x) * pixel_step]; }
};

}  // namespace mallet::input::camera
