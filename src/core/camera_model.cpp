#include "core/camera_model.hpp"

#include <algorithm>
#include <cmath>

namespace mallet {

double v4l2_read_delay_ms(double rate_hz, double exposure_us) {
  const double frame_ms = 1e3 / rate_hz;
  const double exposure_ms = exposure_us > 0 ? std::min(exposure_us * 1e-3, frame_ms) : frame_ms;
  return 0.5 * exposure_ms + frame_ms;
}

CameraModel wii_camera(double rate_hz) {
  CameraModel c;
  c.rate_hz = rate_hz;
  return c;
}

CameraModel v4l2_camera(double rate_hz, double exposure_us) {
  CameraModel c;
  c.name = "v4l2";
  c.rate_hz = rate_hz;
  c.noise_px = kV4l2CentroidNoisePx;
  c.camera_width_px = 640;
  c.quantise_px = false;
  c.drop_probability = 0.005;
  c.read_delay_ms = v4l2_read_delay_ms(rate_hz, exposure_us);
  c.own_stream = true;
  return c;
}

std::vector<CameraModel> every_camera() {
  return {wii_camera(100.0), wii_camera(200.0), v4l2_camera(120.0), v4l2_camera(240.0)};
}

double metres_per_camera_px(const Scene& scene, const CameraModel& camera) {
  return std::fabs(scene.screen_to_world.right_m - scene.screen_to_world.left_m) / camera.camera_width_px;
}

double noise_metres(const Scene& scene, const CameraModel& camera) {
  return camera.noise_px * metres_per_camera_px(scene, camera);
}

}  // namespace mallet
