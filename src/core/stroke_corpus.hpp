#pragma once
// A corpus of human-like strokes with their ground truth, to measure contact prediction
// (core/contact_predictor.hpp) against the exact solver: how early a strike is decided,
// and at what cost in false notes, missed notes and speed error.
//
// Each stroke is a continuous hand path (the sphere centre, world metres) built from
// minimum-jerk segments (Flash & Hogan 1985: x(τ) = x0 + D·(10τ³ − 15τ⁴ + 6τ⁵), the
// profile of a practised reaching movement, peak speed 1.875·D/T). Its true contacts are
// found on the continuous path, so the truth owes nothing to the samples. The path is then
// seen the way the kiosk sees a hand, through a camera model (core/camera_model.hpp: the
// Wii's at 100 and 200 Hz, a V4L2 camera's at 120 and 240 Hz): sampled at its rate with a
// random phase between the contact and the sample grid, Gaussian centroid noise (σ in
// camera pixels, turned into metres through the scene's screen_to_world: one isotropic
// scale over the screen's width), positions quantised to whole camera pixels or not, and
// frames dropped at random. A sample's time is the instant its position is of (the Wii's
// report stamped on arrival, the camera's frame at mid-exposure); the camera's read-out
// after it is CameraModel::read_delay_ms, which the bench adds to every decision.
//
// Deterministic for a seed on every standard library: only std::mt19937's raw output is
// used (its sequence is fixed by the standard); uniforms and normals (Box–Muller) are
// derived here, never through std:: distributions, whose algorithms differ by library; a
// camera's own stream is seeded through std::seed_seq, whose algorithm is fixed too.
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/camera_model.hpp"
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

}  // namespace mallet
