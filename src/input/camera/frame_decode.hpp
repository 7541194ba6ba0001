#pragma once
// A captured frame's bytes → the luma the LED finder reads. GREY and YUYV are read in place
// (no copy: at 240 Hz a 640×480 copy is 74 MB/s for nothing); MJPEG is decoded by
// libjpeg-turbo to 8-bit grayscale only, which skips the chroma's inverse DCT and upsampling.
// Device-free: the capture (v4l2_*) hands frames here, the tests hand generated ones.
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "input/camera/camera_frame.hpp"

namespace mallet::input::camera {

//! The luma of `frame`: a view into frame.bytes for GREY and YUYV (bytes_per_line honoured;
//! YUYV's pixel_step is 2), or into `scratch` (resized to width × height, so a reused
//! vector stops allocating) for MJPEG. The view lives as long as the frame's bytes or the
//! scratch. An error is one line: a size that does not add up ("a 640x480 yuyv frame needs
//! 614400 bytes, this one has 1000"), or "mjpeg frame: " and libjpeg's message for a
//! corrupt or truncated JPEG (its warnings count as errors: a half-decoded frame would put
//! the LED where it is not), or a JPEG whose size is not the frame's.
Result<LumaView, std::string> luma_view(const CameraFrame& frame, std::vector<std::uint8_t>& scratch);

}  // namespace mallet::input::camera
