#pragma once
// `mallet bench input`'s workload: synthetic tracks seen through a model of the Wii Remote's
// camera. The scene's screen_to_world rectangle is the camera's 1024-px-wide view (one
// isotropic scale), 100 Hz, Gaussian noise on each axis, positions quantised to whole pixels
// as the camera reports them; every frame goes through the IrTracker (with a fixed
// reflection in view) and back to world metres. Strikes are ghost_player paths, sampled
// densely as the truth and at 100 Hz with a random phase for the camera.
#include <cstdint>
#include <vector>

#include "core/ghost_player.hpp"
#include "core/ir_tracker.hpp"
#include "core/scene.hpp"
#include "core/time.hpp"

namespace mallet::app::input_bench {

inline constexpr Nanos kFrame = 10'000'000;  //!< 100 Hz
inline constexpr double kNoisePx = 0.5;      //!< σ per axis before quantisation
inline constexpr double kTruthRateHz = 10000;
inline constexpr double kFollowThroughM = 0.03;  //!< the hand goes 3 cm below the bar, then lifts
inline constexpr IrDot kReflection{930, 70, 2};  //!< a fixed glint in the camera's view
//! The strike tracks' middle speeds, m/s (each ± 0.5 within 1..4).
inline constexpr double kStrikeSpeeds[] = {1.0, 2.0, 3.0, 4.0};

struct Camera {
  ScreenToWorld view;
  double m_per_px = 0;
  explicit Camera(const ScreenToWorld& s) : view(s), m_per_px((s.right_m - s.left_m) / 1024.0) {}
  Vec2 to_px(Vec2 w) const { return {(w.x - view.left_m) / m_per_px, (view.top_m - w.y) / m_per_px}; }
  Vec2 to_world(double px, double py) const { return {view.left_m + px * m_per_px, view.top_m - py * m_per_px}; }
};

//! The camera's view of a true path: tracked LED positions back in world metres.
struct Observed {
  std::vector<Nanos> t;
  std::vector<Vec2> raw;   //!< world metres of the quantised, noisy camera dot
  std::vector<Vec2> truth; //!< world metres, exact, at the same times
};

struct TrackerTally {
  std::uint64_t frames = 0, accepted = 0, rejected = 0, jumps = 0, lost = 0;
  double max_px_per_s = 0;
};

//! A piecewise-linear path sampled densely; evaluated by interpolation.
struct TruePath {
  std::vector<PointerSample> s;
  Vec2 at(Nanos t) const {
    if (t <= s.front().t_ns) return {s.front().x, s.front().y};
    if (t >= s.back().t_ns) return {s.back().x, s.back().y};
    const auto it = std::lower_bound(s.begin(), s.end(), t, [](const PointerSample& p, Nanos v) { return p.t_ns < v; });
    const PointerSample& b = *it;
    const PointerSample& a = *(it - 1);
    const double u = double(t - a.t_ns) / double(b.t_ns - a.t_ns);
    return {a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u};
  }
  double speed(Nanos t) const {
    const Nanos h = 500'000;
    const Vec2 a = at(t - h), b = at(t + h);
    return std::hypot(b.x - a.x, b.y - a.y) / (2e-9 * double(h));
  }
};

struct StrikeTrack {
  TruePath path;
  Observed obs;
  std::vector<ScriptedStrike> strikes;
  std::vector<Nanos> contacts;
  std::vector<std::size_t> moving;  //!< observed samples where the hand moves > 0.3 m/s
};

//! The synthetic workload every measurement here runs on, in one fixed order of random
//! draws (so the tables are deterministic for a seed).
struct Workload {
  explicit Workload(const Scene& scene) : cam(scene.screen_to_world) {}
  Camera cam;
  TrackerTally tally;
  std::vector<Observed> still;
  std::uint64_t resting_strikes = 0, resting_frames = 0;
  std::vector<StrikeTrack> tracks;
  std::vector<StrikeTrack> slow;
};

//! The workload for `seed`: `still_tracks` still hands (10 s each), a hand resting on each
//! bar's contact plane, 4 strike tracks of `strikes_per_track` strikes (kStrikeSpeeds), and
//! 4 slowly circling hands (aiming).
Workload make_workload(const Scene& scene, std::uint64_t seed, int strikes_per_track, int still_tracks = 12);

}  // namespace mallet::app::input_bench
