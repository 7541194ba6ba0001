#pragma once
// How a tracker's camera sees the hand, as the stroke corpus (core/stroke_corpus.hpp)
// models it and as contact prediction is tuned for it (core/camera_prediction.hpp): its
// rate, centroid noise, pixel scale, drops, and the delay from a sample's time to the
// kiosk holding it. Two cameras are modelled:
//  * "wii": the Wii Remote's camera at 100 and 200 Hz: 1024 px over the screen's width
//    (≈0.82 mm/px for the shipped percussion scene), σ 0.5 px, whole pixels, 2 % dropped.
//    Its report is stamped on arrival, so nothing lies between its time and the kiosk
//    holding it: read delay 0.
//  * "v4l2": a V4L2 camera at 640×480 behind an IR filter, at 120 and 240 Hz: 640 px over
//    the width (≈1.3 mm/px), an intensity-weighted centroid (subpixel, not quantised),
//    σ kV4l2CentroidNoisePx, 0.5 % of frames dropped. Its frame is stamped at mid-exposure
//    (the kernel's stamp moved there, input/camera/frame_stamp.hpp) but the kiosk holds it
//    only once it has been read out and sent over USB: v4l2_read_delay_ms.
#include <string_view>
#include <vector>

#include "core/scene.hpp"

namespace mallet {

//! How one camera at one rate sees the hand (the corpus's observation model).
struct CameraModel {
  std::string_view name = "wii";   //!< what the bench's rows call it
  double rate_hz = 100;
  double noise_px = 0.5;           //!< centroid noise σ per axis, camera pixels
  double camera_width_px = 1024;   //!< over the screen's width (isotropic pixels)
  bool quantise_px = true;         //!< whole camera pixels (the Wii); false: subpixel centroids
  double drop_probability = 0.02;  //!< each frame independently
  //! From a sample's time to the kiosk holding it; the bench decides a strike then.
  double read_delay_ms = 0;
  //! Where its phase, noise and drops are drawn. false: from the corpus's one stream, right
  //! after the shape's path (how the Wii corpus has always been drawn, so its strokes for a
  //! seed stay bit for bit what they were; adding or removing such a camera changes every
  //! later shape). true: from a stream of its own, seeded by the corpus seed, the shape and
  //! the rate, so adding or removing it changes no other stroke.
  bool own_stream = false;
};

//! The V4L2 camera's centroid noise, σ per axis in camera pixels: `mallet bench input`'s
//! centroid-noise table (the LED finder on synthetic frames of a still LED, read noise 1.5
//! grey levels + shot noise: 0.020 px RMS per axis; 0.014 with a quieter sensor, 0.037
//! with a noisier one). `mallet bench prediction --camera-noise-px` shows other values.
inline constexpr double kV4l2CentroidNoisePx = 0.020;
//! [camera] exposure_us's default: the exposure the corpus's V4L2 camera runs at.
inline constexpr double kV4l2ExposureUs = 500;

//! From a V4L2 frame's stamp (mid-exposure) to the kiosk holding its sample: the rest of
//! the exposure (half of it) and the frame's read-out and USB transfer. A camera run at
//! its full rate reads its rows out over about one frame interval and a UVC camera sends
//! them as it reads, so the last packet lands about one frame after the exposure ended:
//! exposure/2 + 1/rate (240 Hz at 500 µs: 4.42 ms; 120 Hz: 8.58 ms). Finding the LED
//! (< 0.1 ms a frame, bench input) is left out. An automatic exposure (0) is taken as a
//! whole frame, its longest.
double v4l2_read_delay_ms(double rate_hz, double exposure_us);

//! The Wii Remote's camera at `rate_hz` (100 or 200): the defaults above.
CameraModel wii_camera(double rate_hz);
//! A 640×480 V4L2 camera at `rate_hz` (120 or 240): subpixel centroids, σ
//! kV4l2CentroidNoisePx, read delay v4l2_read_delay_ms(rate_hz, exposure_us).
CameraModel v4l2_camera(double rate_hz, double exposure_us = kV4l2ExposureUs);
//! Every camera at every rate the kiosk runs: the Wii at 100 and 200 Hz, then the V4L2
//! camera at 120 and 240 Hz (the bench's corpus).
std::vector<CameraModel> every_camera();

//! Metres per camera pixel for a scene's screen mapping (the noise model's scale).
double metres_per_camera_px(const Scene& scene, const CameraModel& camera);
//! The camera's centroid noise on the scene, σ metres (noise_px × metres_per_camera_px).
double noise_metres(const Scene& scene, const CameraModel& camera);

}  // namespace mallet
