#pragma once
// A corpus of human-like strokes with their ground truth, to measure contact prediction
// (core/contact_predictor.hpp) against the exact solver: how early a strike is decided,
// and at what cost in false notes, missed notes and speed error.
//
// Each stroke is a continuous hand path (the sphere centre, world metres) built from
// minimum-jerk segments (Flash & Hogan 1985: x(τ) = x0 + D·(10τ³ − 15τ⁴ + 6τ⁵), the
// profile of a practised reaching movement, peak speed 1.875·D/T). Its true contacts are
// found on the continuous path, so the truth owes nothing to the samples. The path is then
// seen the way the kiosk sees a hand, through a camera model (CameraModel): sampled at its
// rate with a random phase between the contact and the sample grid, Gaussian centroid
// noise (σ in camera pixels, turned into metres through the scene's screen_to_world: one
// isotropic scale over the screen's width), positions quantised to whole camera pixels or
// not, and frames dropped at random. Two cameras are modelled:
//  * "wii": the Wii Remote's camera at 100 and 200 Hz: 1024 px over the screen's width
//    (≈0.82 mm/px for the shipped percussion scene), σ 0.5 px, whole pixels, 2 % dropped.
//  * "v4l2": any V4L2 camera at 640×480 behind an IR filter, at 120 and 240 Hz: 640 px over
//    the width (≈1.3 mm/px), an intensity-weighted centroid (subpixel, not quantised),
//    σ kV4l2CentroidNoisePx, 0.5 % of frames dropped.
// A sample's time is the instant its position is of (the Wii's report stamped on arrival,
// the camera's frame at mid-exposure) and the bench decides a strike there: neither the
// Wii's radio nor the camera's read-out (at most one frame interval) is in the model
// (CameraModel::read_delay_ms is 0 for both), so the two cameras' rows compare like for like.
//
// Deterministic for a seed on every standard library: only std::mt19937's raw output is
// used (its sequence is fixed by the standard); uniforms and normals (Box–Muller) are
// derived here, never through std:: distributions, whose algorithms differ by library; a
// camera's own stream is seeded through std::seed_seq, whose algorithm is fixed too.
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/enum_names.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"

namespace mallet {

//! What a stroke is; the bench reports every kind, the tests check every kind is made.
enum class StrokeKind {
  strike,         //!< a downswing through a bar at 0.2–4 m/s peak, the bottom below the bar
  slow_approach,  //!< the hand brakes 3–15 mm above a bar, then touches it at 0.1–0.5 m/s
  stop_above,     //!< the hand brakes and stops 0–10 mm above a bar: no contact
  hover,          //!< the hand waits 3–30 mm above a bar, with tremor and drift: no contact
  slide,          //!< along the bars: on them after a strike (one contact), or just above (none)
  double_tap,     //!< two strikes on one bar, the hand rising 6–20 mm between them
};
inline constexpr EnumNames<StrokeKind, 6> kStrokeKindNames{{
    {StrokeKind::strike, "strike"}, {StrokeKind::slow_approach, "slow_approach"},
    {StrokeKind::stop_above, "stop_above"}, {StrokeKind::hover, "hover"}, {StrokeKind::slide, "slide"},
    {StrokeKind::double_tap, "double_tap"}}};
inline constexpr int kStrokeKinds = 6;
const char* to_string(StrokeKind kind);

//! One true contact of the noise-free path with a bar's top.
struct TrueContact {
  Nanos t_ns = 0;              //!< when the sphere's bottom meets the bar's top
  int target = -1;             //!< Target::id
  double speed_m_per_s = 0;    //!< downward (normal) speed of the hand at that instant
};

struct Stroke {
  StrokeKind kind = StrokeKind::strike;
  int shape = 0;               //!< index of the continuous path: the same for every camera
  std::string_view camera = "wii";  //!< CameraModel::name
  double rate_hz = 100;
  std::vector<PointerSample> samples;  //!< world metres (x, y), as GhostPath's samples
  std::vector<TrueContact> contacts;   //!< in time order; empty: the stroke must make no note
  //! Lowest height of the noise-free path above the contact plane of the bar under it,
  //! over the stretches where it is not in contact (metres; large when never over a bar).
  double min_clearance_m = 0;
  double peak_speed_m_per_s = 0;       //!< of the noise-free path's fastest segment
};

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

//! The camera's centroid noise, σ per axis in camera pixels (measured on the tracker: 0.05–0.15).
inline constexpr double kV4l2CentroidNoisePx = 0.1;

//! The Wii Remote's camera at `rate_hz` (100 or 200): the defaults above.
CameraModel wii_camera(double rate_hz);
//! A 640×480 V4L2 camera at `rate_hz` (120 or 240): subpixel centroids, σ kV4l2CentroidNoisePx.
CameraModel v4l2_camera(double rate_hz);
//! Every camera at every rate the kiosk runs: the Wii at 100 and 200 Hz, then the V4L2
//! camera at 120 and 240 Hz (the bench's corpus).
std::vector<CameraModel> every_camera();

struct CorpusConfig {
  std::uint32_t seed = 1;
  int shapes_per_kind = 200;
  //! Each shape is seen by each camera, in this order.
  std::vector<CameraModel> cameras{wii_camera(100.0), wii_camera(200.0)};
};

//! Every shape of every kind, each seen by every camera: shapes_per_kind · 6 · cameras
//! strokes, grouped by shape (shape i's strokes, one per camera in config order, are
//! adjacent, and share one continuous path and its truth). The scene must have targets;
//! strokes use its bars and its screen mapping.
std::vector<Stroke> make_stroke_corpus(const Scene& scene, const CorpusConfig& config);

//! Metres per camera pixel for a scene's screen mapping (the noise model's scale).
double metres_per_camera_px(const Scene& scene, const CameraModel& camera);

}  // namespace mallet
