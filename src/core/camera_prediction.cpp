#include "core/camera_prediction.hpp"

#include <algorithm>
#include <cmath>


namespace mallet {

PredictionConfig prediction_for_camera(const PredictionConfig& preset, double rate_hz, double noise_m,
                                       double read_delay_ms) {
  PredictionConfig c = preset;
  if (!(c.horizon_ms > 0) || !(rate_hz > 0) || !std::isfinite(rate_hz)) return c;
  // Only ever shortened: a preset that already fits fewer samples keeps its window.
  c.fit_window_ms = std::min(c.fit_window_ms, kCameraFitWindowFrames * 1e3 / rate_hz);
  if (noise_m >= 0 && std::isfinite(noise_m)) c.noise_m = noise_m;
  // Across the read-out only when the next frame arrives within the horizon: at 120 Hz
  // (16.9 ms) reaching the horizon's 10 ms instead of the frame's 8.3 bought 0.02 ms at the
  // median and cost two false notes on the bench's corpus.
  const double next_held_ms = 1e3 / rate_hz + read_delay_ms;
  if (read_delay_ms >= 0 && next_held_ms <= c.horizon_ms) c.sample_delay_ms = read_delay_ms;
  return c;
}

PredictionConfig prediction_for_camera(const PredictionConfig& preset, const CameraModel& camera, const Scene& scene) {
  return prediction_for_camera(preset, camera.rate_hz, noise_metres(scene, camera), camera.read_delay_ms);
}

CameraRouteTiming camera_route_timing(const AppConfig& config, const Scene& scene) {
  CameraModel model = v4l2_camera(config.camera.rate_hz, config.camera.exposure_us);
  model.camera_width_px = config.camera.width;
  CameraRouteTiming t;
  t.noise_m = noise_metres(scene, model);
  t.read_delay_ms = model.read_delay_ms;
  t.predict = prediction_for_camera(config.timing.predict, model, scene);
  return t;
}

}  // namespace mallet
