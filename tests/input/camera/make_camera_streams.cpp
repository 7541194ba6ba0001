// Writes the kept camera streams of tests/input/camera (README.md there says when and how):
//   make_camera_streams DIR
// Deterministic: the same files on every machine whose exp and erf round alike (Box–Muller
// on std::mt19937's raw output; MJPEG by the libjpeg-turbo the build links).
#include <cstdio>
#include <exception>
#include <filesystem>

#include "input/camera/frame_stream.hpp"

namespace cam = mallet::input::camera;
using cam::test::StreamSpec;

namespace {

// 160×120 covering the kiosk's 0.82 m: 5.125 mm a pixel; 240 frames a second, 1 ms exposure.
constexpr double kMmPerPx = 820.0 / 160.0;
constexpr double px_per_s(double m_per_s) { return m_per_s * 1000.0 / kMmPerPx; }

StreamSpec base(std::uint32_t seed) {
  StreamSpec s;
  s.scene.width = 160;
  s.scene.height = 120;
  s.scene.background = 12;
  s.scene.read_noise = 1.5;
  s.scene.shot_variance_per_level = 0.1;
  s.scene.exposure_s = 0.001;
  s.rate_hz = 240;
  s.seed = seed;
  s.led.sigma_px = 1.3;
  s.led.peak = 170;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_camera_streams DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  try {
    // A still LED with sensor noise: the centroid's noise, frame after frame.
    StreamSpec still = base(11);
    still.format = cam::PixelFormat::grey;
    still.frames = 30;
    still.led.x = 81.3;
    still.led.y = 57.6;
    cam::test::write_frame_stream(dir / "still_led.stream", cam::test::make_frame_stream(still));

    // The LED moving at 2 m/s diagonally past a second, dimmer light that stays put; MJPEG.
    StreamSpec moving = base(12);
    moving.format = cam::PixelFormat::mjpeg;
    moving.frames = 40;
    moving.led.x = 30.2;
    moving.led.y = 40.7;
    moving.led.vx_px_per_s = 0.8 * px_per_s(2.0);
    moving.led.vy_px_per_s = 0.6 * px_per_s(2.0);
    moving.reflection = cam::SynthSpot{70.0, 52.0, 1.3, 80.0, 0.0, 0.0};
    cam::test::write_frame_stream(dir / "moving_led.stream", cam::test::make_frame_stream(moving));

    // The LED at 1 m/s with frames the driver dropped; YUYV with padded rows.
    StreamSpec dropped = base(13);
    dropped.format = cam::PixelFormat::yuyv;
    dropped.bytes_per_line = 336;
    dropped.frames = 16;
    dropped.led.x = 40.4;
    dropped.led.y = 70.1;
    dropped.led.vx_px_per_s = px_per_s(1.0);
    dropped.dropped = {4, 5, 9, 10, 11};
    cam::test::write_frame_stream(dir / "dropped_frames.stream", cam::test::make_frame_stream(dropped));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_camera_streams: %s\n", e.what());
    return 1;
  }
  return 0;
}
