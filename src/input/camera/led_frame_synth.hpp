#pragma once
// Synthetic IR camera frames: what an 850 nm-filtered camera with a short exposure sees of
// the stick's LED. One generator for the tests' kept streams and `mallet bench input`.
//
// Model, per pixel centre (x, y) in pixel units (pixel centres at integer coordinates):
//   luma = background + Σ spots + noise, rounded and clamped to 0..255
// A spot is a Gaussian of `sigma_px` and `peak` grey levels above the background. Motion
// blur: the spot's centre moves at constant velocity during the exposure, from
// centre − v·T/2 to centre + v·T/2; the frame integrates it, which for a Gaussian is closed
// form (erf along the motion, Gaussian across it), so the blurred spot's centroid is
// exactly the exposure's middle. Noise: read noise of `read_noise` grey levels plus shot
// noise whose variance is `shot_variance_per_level` × the signal above the background
// (i.e. 1 / the sensor's electrons per grey level), drawn with Box–Muller from a seeded
// std::mt19937's raw output (no std:: distribution: theirs differ between libraries, and
// the kept streams must not).
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "input/camera/camera_frame.hpp"

namespace mallet::input::camera {

//! One light in view: the LED or a reflection / second light.
struct SynthSpot {
  double x = 0, y = 0;           //!< the centre at the exposure's middle, px
  double sigma_px = 1.5;         //!< the Gaussian's σ
  double peak = 200;             //!< grey levels above the background (before clamping)
  double vx_px_per_s = 0, vy_px_per_s = 0;  //!< velocity: blur = v × exposure
};

struct SynthScene {
  int width = 640;
  int height = 480;
  double background = 12;                //!< grey levels: an IR-filtered room, short exposure
  double read_noise = 1.5;               //!< σ of the read noise, grey levels
  double shot_variance_per_level = 0.1;  //!< shot noise: variance (levels²) per level of signal
  double exposure_s = 0.001;
  std::vector<SynthSpot> spots;
};

//! Draws frames of SynthScenes; deterministic for a seed (the same frames on every machine
//! that rounds exp and erf the same way).
class LedFrameSynth {
 public:
  explicit LedFrameSynth(std::uint32_t seed) : rng_(seed) {}

  //! `scene` as 8-bit luma, width × height, row-major, into `luma` (resized).
  void render(const SynthScene& scene, std::vector<std::uint8_t>& luma);
  //! A standard normal draw (Box–Muller on two raw 32-bit draws, the second value kept).
  double normal();

 private:
  std::mt19937 rng_;
  std::optional<double> spare_;
};

//! The noiseless brightness of `spot` at (x, y) above the background, blurred over `exposure_s`.
double spot_level(const SynthSpot& spot, double exposure_s, double x, double y);

//! `luma` (width × height, packed) as a camera in `format` would send it: GREY as it is; YUYV
//! with neutral chroma (128) and rows of `bytes_per_line` (0 = packed); MJPEG by libjpeg at
//! `jpeg_quality`, 4:2:2 like a UVC webcam. An error only if libjpeg refuses.
Result<std::vector<std::uint8_t>, std::string> encode_frame(const std::vector<std::uint8_t>& luma, int width,
                                                            int height, PixelFormat format,
                                                            std::size_t bytes_per_line = 0, int jpeg_quality = 90);

}  // namespace mallet::input::camera
