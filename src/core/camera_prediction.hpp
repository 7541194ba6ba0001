#pragma once
// Contact prediction (core/contact_predictor.hpp) tuned for a camera tracker. The presets
// were chosen on the Wii's camera (100 Hz, σ ≈0.4 mm, its report held as soon as it is
// stamped); a V4L2 camera differs in the three things the predictor's knobs are about,
// and `mallet bench prediction` (its "eager*", "balanced*", "exact*" rows) measured what
// each change buys on the stroke corpus:
//  * its noise (σ ≈0.025 mm, bench input): noise_m is the camera's, so the uncertainty
//    test weighs the real noise and not the Wii's 20× larger default;
//  * its rate: the fit window is at most 4.5 frames (5 samples: 18.75 ms at 240 Hz; at
//    120 Hz the preset's 35 ms is shorter than that and stays). A short window follows a
//    stroke that has just turned (a double tap's second downswing, a gentle touch after a
//    pause) before it is over; the camera's low noise is what lets so few samples be
//    fitted. 3.5 frames (4 samples) did as well on the corpus but broke the could_stop
//    guarantee (a 4-sample quadratic lags a hand's braking too much);
//  * its read-out: a frame is held v4l2_read_delay_ms after its mid-exposure stamp
//    (4.4 ms at 240 Hz, 8.6 ms at 120 Hz), so sample_delay_ms lets a crossing be predicted
//    up to the next frame's arrival instead of its exposure, when that arrival is within
//    the preset's horizon (240 Hz: 8.6 ≤ 10 ms; not 120 Hz: 16.9 ms).
// The price is speed: extrapolated twice as far, a quadratic reads a braking hand's speed
// higher (balanced* at 240 Hz: p99 speed error on strikes ≥ 1 m/s ≈90 % against the
// solver's 21 % and the untuned preset's 35 %). Only the camera's strike route uses it:
// the Wii's stays the preset, bit for bit.
#include "core/app_config.hpp"
#include "core/camera_model.hpp"
#include "core/contact_predictor.hpp"
#include "core/scene.hpp"

namespace mallet {

//! Frames of the camera's fit window, at most (4.5: five samples; see above).
inline constexpr double kCameraFitWindowFrames = 4.5;

//! `preset` (a [timing] predict_confidence level with its horizon) tuned for a camera
//! delivering `rate_hz` frames a second, its hand heights noisy by σ `noise_m` metres, each
//! frame held `read_delay_ms` after its time (v4l2_read_delay_ms). Prediction off
//! (horizon_ms 0) stays off; a rate that is not positive leaves the preset as it is.
PredictionConfig prediction_for_camera(const PredictionConfig& preset, double rate_hz, double noise_m,
                                       double read_delay_ms);

//! The same for a modelled camera on `scene` (its rate, its noise in metres, its read delay):
//! what the bench's starred rows and the kiosk's camera route run.
PredictionConfig prediction_for_camera(const PredictionConfig& preset, const CameraModel& camera, const Scene& scene);

//! How the kiosk's camera route times its strikes, from the settings: the camera modelled at
//! [camera] rate_hz, exposure_us and width (core/camera_model.hpp; its noise in metres on
//! `scene`) and [timing]'s prediction tuned for it. The live route and `simulate --causal
//! --camera` both take it from here.
struct CameraRouteTiming {
  PredictionConfig predict;
  double noise_m = 0;        //!< the centroid's noise on the scene, σ metres
  double read_delay_ms = 0;  //!< from a frame's mid-exposure to the kiosk holding it
};
CameraRouteTiming camera_route_timing(const AppConfig& config, const Scene& scene);

}  // namespace mallet
