#include "core/stroke_corpus.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "core/mallet.hpp"

namespace mallet {

const char* to_string(StrokeKind kind) { return name_in(kStrokeKindNames, kind); }

namespace {

//! No segment accelerates or brakes harder than this (≈12 g at the mallet's head): a hand
//! swinging a stick in the air, not a stick rebounding from a drum head.
constexpr double kMaxAccelMPerS2 = 120.0;
//! Minimum-jerk peak acceleration is (10/√3)·D/T² ≈ 5.77·D/T².
constexpr double kMinJerkAccelFactor = 5.7735;
constexpr double kMinJerkPeakSpeedFactor = 1.875;  //!< peak speed = 1.875·D/T
constexpr double kRearmHeightM = 0.003;            //!< ContactConfig's default hysteresis
constexpr double kTruthStepS = 1e-4;               //!< scan step of the noise-free path

//! Uniforms and normals from std::mt19937's raw 32-bit output only (portable).
class Rng {
 public:
  explicit Rng(std::uint32_t seed) : engine_(seed) {}
  explicit Rng(std::seed_seq& seeds) : engine_(seeds) {}
  //! In (0, 1), never 0 (Box–Muller takes its log).
  double unit() { return (static_cast<double>(engine_()) + 0.5) * 0x1p-32; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  int index(int n) { return std::min(n - 1, static_cast<int>(unit() * n)); }
  bool coin() { return unit() < 0.5; }
  double normal() {
    if (spare_) {
      const double z = *spare_;
      spare_.reset();
      return z;
    }
    const double r = std::sqrt(-2.0 * std::log(unit()));
    const double phi = 2.0 * std::numbers::pi * unit();
    spare_ = r * std::sin(phi);
    return r * std::cos(phi);
  }

 private:
  std::mt19937 engine_;
  std::optional<double> spare_;
};

//! A minimum-jerk move from p0 to p1 over [t0, t1] (seconds from the path's start).
struct Segment {
  double t0, t1;
  Vec2 p0, p1;
};

struct Tremor {
  double amp_m = 0, freq_hz = 0, phase = 0;
};

//! The continuous hand path: contiguous segments (a hold is a segment with p0 == p1).
class Path {
 public:
  explicit Path(Vec2 start) : end_(start) {}

  void hold(double seconds) { move_to(end_, seconds); }
  void move_to(Vec2 p, double seconds) {
    segments_.push_back({t_end_, t_end_ + seconds, end_, p});
    t_end_ += seconds;
    end_ = p;
  }
  //! A move whose duration follows from its peak speed, lengthened to respect kMaxAccel.
  void move_at(Vec2 p, double peak_speed_m_per_s) {
    const double d = std::hypot(p.x - end_.x, p.y - end_.y);
    double t = kMinJerkPeakSpeedFactor * d / peak_speed_m_per_s;
    t = std::max({t, std::sqrt(kMinJerkAccelFactor * d / kMaxAccelMPerS2), 1e-3});
    move_to(p, t);
  }
  void set_tremor(Tremor t) { tremor_ = t; }

  double duration() const { return t_end_; }
  Vec2 end() const { return end_; }

  Vec2 at(double t) const {
    const Segment& s = segment(t);
    const double u = normalised(s, t);
    const double k = ((6.0 * u - 15.0) * u + 10.0) * u * u * u;
    Vec2 p = lerp(s.p0, s.p1, k);
    p.y += tremor(t);
    return p;
  }
  Vec2 velocity(double t) const {
    const Segment& s = segment(t);
    const double u = normalised(s, t);
    const double dk = 30.0 * u * u * (1.0 - u) * (1.0 - u) / (s.t1 - s.t0);
    const double w = 2.0 * std::numbers::pi * tremor_.freq_hz;
    return {(s.p1.x - s.p0.x) * dk, (s.p1.y - s.p0.y) * dk + tremor_.amp_m * w * std::cos(w * t + tremor_.phase)};
  }
  double peak_speed() const {
    double v = 0;
    for (const Segment& s : segments_)
      v = std::max(v, kMinJerkPeakSpeedFactor * std::hypot(s.p1.x - s.p0.x, s.p1.y - s.p0.y) / (s.t1 - s.t0));
    return v;
  }

 private:
  const Segment& segment(double t) const {
    for (const Segment& s : segments_)
      if (t < s.t1) return s;
    return segments_.back();
  }
  static double normalised(const Segment& s, double t) { return std::clamp((t - s.t0) / (s.t1 - s.t0), 0.0, 1.0); }
  double tremor(double t) const {
    return tremor_.amp_m * std::sin(2.0 * std::numbers::pi * tremor_.freq_hz * t + tremor_.phase);
  }

  std::vector<Segment> segments_;
  double t_end_ = 0;
  Vec2 end_;
  Tremor tremor_;
};

Nanos to_ns(double seconds) { return static_cast<Nanos>(std::llround(seconds * 1e9)); }

//! The noise-free path's contacts under the contact model (a downward crossing of a
//! zone's plane while armed; re-armed kRearmHeightM above the plane touched), and its
//! lowest height above a plane while not in contact.
void find_truth(const Path& path, const std::vector<ContactZone>& zones, Nanos origin, Stroke& out) {
  out.min_clearance_m = 1e9;
  bool armed = true;
  double rearm_y = 0;
  Vec2 prev = path.at(0);
  if (const ContactZone* z = zone_at(zones, prev); z && prev.y <= z->plane_y) {
    armed = false;
    rearm_y = z->plane_y + kRearmHeightM;
  }
  const int steps = static_cast<int>(std::ceil(path.duration() / kTruthStepS));
  for (int i = 1; i <= steps; ++i) {
    const double t1 = std::min(path.duration(), i * kTruthStepS);
    const double t0 = (i - 1) * kTruthStepS;
    const Vec2 p = path.at(t1);
    const ContactZone* z = zone_at(zones, p);
    if (z && p.y <= z->plane_y) {
      if (armed && prev.y > z->plane_y) {
        double lo = t0, hi = t1;  // bisection: y(lo) > plane >= y(hi)
        for (int k = 0; k < 60; ++k) {
          const double mid = 0.5 * (lo + hi);
          (path.at(mid).y > z->plane_y ? lo : hi) = mid;
        }
        out.contacts.push_back({origin + to_ns(hi), z->target, -path.velocity(hi).y});
      }
      armed = false;
      rearm_y = z->plane_y + kRearmHeightM;
    } else {
      if (z) out.min_clearance_m = std::min(out.min_clearance_m, p.y - z->plane_y);
      if (!armed && p.y >= rearm_y) armed = true;
    }
    prev = p;
  }
}

double plane_of(const Scene& scene, const Target& bar) { return bar.top_y + scene.mallet_radius_m; }

//! A peak speed and travel for a downswing: 0.2–4 m/s (log-uniform), 0.1–0.35 s, the
//! travel kept within 2–30 cm (the screen's height).
struct Swing {
  double peak_m_per_s, travel_m;
};
Swing random_swing(Rng& rng) {
  const double v = rng.log_uniform(0.2, 4.0);
  const double t = rng.uniform(0.1, 0.35);
  return {v, std::clamp(v * t / kMinJerkPeakSpeedFactor, 0.02, 0.30)};
}

//! A bar and an x on its top face.
const Target& random_bar(const Scene& scene, Rng& rng, double& x) {
  const Target& bar = scene.targets[static_cast<std::size_t>(rng.index(static_cast<int>(scene.targets.size())))];
  x = rng.uniform(bar.x_min, bar.x_max);
  return bar;
}

//! Down through (or to) `bottom_y` from `travel` above it, with a small sideways drift
//! that stays on the bar's top face; then the hand rests there.
Path downswing(const Target& bar, double x, double bottom_y, const Swing& s, Rng& rng) {
  const double drift = rng.uniform(-0.003, 0.003);
  const double x_end = std::clamp(x + drift, bar.x_min, bar.x_max);
  Path path({x, bottom_y + s.travel_m});
  path.hold(rng.uniform(0.08, 0.15));
  path.move_at({x_end, bottom_y}, s.peak_m_per_s);
  path.hold(rng.uniform(0.02, 0.06));
  return path;
}

void lift(Path& path, double to_y, Rng& rng) {
  path.move_to({path.end().x, to_y}, rng.uniform(0.2, 0.4));
  path.hold(0.1);
}

Path make_strike(const Scene& scene, Rng& rng) {
  double x = 0;
  const Target& bar = random_bar(scene, rng, x);
  const Swing s = random_swing(rng);
  // The bottom lies past the bar: the contact falls anywhere from peak speed to late in
  // the braking (8–50 % of the travel left), never more than 9 cm below.
  const double depth = std::min(0.09, s.travel_m * rng.uniform(0.08, 0.5));
  Path path = downswing(bar, x, plane_of(scene, bar) - depth, s, rng);
  lift(path, plane_of(scene, bar) + s.travel_m - depth, rng);
  return path;
}

Path make_slow_approach(const Scene& scene, Rng& rng) {
  double x = 0;
  const Target& bar = random_bar(scene, rng, x);
  const double plane = plane_of(scene, bar);
  // A swing that brakes 3–15 mm above the bar (exactly like a stop_above, so far), a
  // pause of up to 0.1 s, then a gentle touch at 0.1–0.5 m/s ending 1–6 mm past the top.
  Path path = downswing(bar, x, plane + rng.uniform(0.003, 0.015), random_swing(rng), rng);
  path.hold(rng.uniform(0.0, 0.08));
  path.move_at({path.end().x, plane - rng.uniform(0.001, 0.006)}, rng.uniform(0.1, 0.5));
  path.hold(rng.uniform(0.02, 0.06));
  lift(path, plane + 0.05, rng);
  return path;
}

Path make_stop_above(const Scene& scene, Rng& rng) {
  double x = 0;
  const Target& bar = random_bar(scene, rng, x);
  const Swing s = random_swing(rng);
  const double h = rng.uniform(0.0, 0.010);
  Path path = downswing(bar, x, plane_of(scene, bar) + h, s, rng);
  path.hold(rng.uniform(0.1, 0.4));
  lift(path, plane_of(scene, bar) + 0.05, rng);
  return path;
}

Path make_hover(const Scene& scene, Rng& rng) {
  double x = 0;
  const Target& bar = random_bar(scene, rng, x);
  const double h = rng.uniform(0.003, 0.030);
  const double plane = plane_of(scene, bar);
  Path path({x, plane + h + rng.uniform(0.02, 0.08)});
  path.hold(0.1);
  path.move_at({x, plane + h}, rng.uniform(0.2, 0.8));
  // Slow drift up and down around the height, never below half of it with the tremor.
  const double drift = rng.uniform(0.0, std::min(0.002, 0.3 * h));
  const double hover_s = rng.uniform(0.5, 1.5);
  for (double t = 0; t < hover_s;) {
    const double step = rng.uniform(0.2, 0.4);
    path.move_to({std::clamp(x + rng.uniform(-0.002, 0.002), bar.x_min, bar.x_max), plane + h + rng.uniform(-drift, drift)}, step);
    t += step;
  }
  path.set_tremor({rng.uniform(0.0001, std::min(0.0008, 0.2 * h)), rng.uniform(6.0, 10.0), rng.uniform(0.0, 6.28)});
  lift(path, plane + 0.05, rng);
  return path;
}

Path make_slide(const Scene& scene, Rng& rng) {
  const Instrument& inst = scene.instruments[static_cast<std::size_t>(rng.index(static_cast<int>(scene.instruments.size())))];
  const Target& first = scene.targets[static_cast<std::size_t>(inst.targets.front())];
  const Target& last = scene.targets[static_cast<std::size_t>(inst.targets.back())];
  const bool rightwards = rng.coin();
  const Target& from = rightwards ? first : last;
  const double x0 = rng.uniform(from.x_min, from.x_max);
  const double span = std::min(rng.uniform(0.06, 0.20), last.x_max - first.x_min - 0.01);
  const double x1 = std::clamp(x0 + (rightwards ? span : -span), first.x_min, last.x_max);
  const double plane = plane_of(scene, from);
  const double speed = rng.uniform(0.1, 0.5);
  if (rng.coin()) {  // on the bars: struck, then dragged along them
    const double depth = rng.uniform(0.002, 0.008);
    Path path = downswing(from, x0, plane - depth, {rng.uniform(0.3, 2.0), rng.uniform(0.03, 0.1)}, rng);
    path.move_at({x1, plane - depth}, speed * kMinJerkPeakSpeedFactor);
    lift(path, plane + 0.05, rng);
    return path;
  }
  // Just above them: lowered slowly, dragged, lifted.
  const double h = rng.uniform(0.002, 0.015);
  Path path({x0, plane + h + rng.uniform(0.02, 0.06)});
  path.hold(0.1);
  path.move_at({x0, plane + h}, rng.uniform(0.1, 0.5));
  path.hold(0.1);
  path.move_at({x1, plane + h}, speed * kMinJerkPeakSpeedFactor);
  lift(path, plane + 0.05, rng);
  return path;
}

Path make_double_tap(const Scene& scene, Rng& rng) {
  double x = 0;
  const Target& bar = random_bar(scene, rng, x);
  const double plane = plane_of(scene, bar);
  const double v1 = rng.uniform(0.3, 3.0);
  const double d1 = rng.uniform(0.002, 0.010);
  Path path = downswing(bar, x, plane - d1, {v1, rng.uniform(0.02, 0.08) + d1}, rng);
  const double rise = rng.uniform(0.006, 0.020);
  path.move_to({x, plane + rise}, rng.uniform(0.05, 0.10));
  const double d2 = rng.uniform(0.002, 0.010);
  path.move_at({x, plane - d2}, v1 * rng.uniform(0.5, 1.0));
  path.hold(rng.uniform(0.02, 0.05));
  lift(path, plane + 0.05, rng);
  return path;
}

Path make_path(StrokeKind kind, const Scene& scene, Rng& rng) {
  switch (kind) {
    case StrokeKind::strike: return make_strike(scene, rng);
    case StrokeKind::slow_approach: return make_slow_approach(scene, rng);
    case StrokeKind::stop_above: return make_stop_above(scene, rng);
    case StrokeKind::hover: return make_hover(scene, rng);
    case StrokeKind::slide: return make_slide(scene, rng);
    case StrokeKind::double_tap: return make_double_tap(scene, rng);
  }
  return make_strike(scene, rng);
}

//! The camera's view of the path, the grid at a random phase.
std::vector<PointerSample> observe(const Path& path, Nanos origin, const CameraModel& camera, const Scene& scene,
                                   Rng& rng) {
  const ScreenToWorld& view = scene.screen_to_world;
  const double m_per_px = metres_per_camera_px(scene, camera);
  const double phase = rng.unit();
  std::vector<PointerSample> out;
  for (long k = 0;; ++k) {
    const double t = (static_cast<double>(k) + phase) / camera.rate_hz;
    if (t > path.duration()) break;
    const Vec2 p = path.at(t);
    double px = (p.x - view.left_m) / m_per_px + camera.noise_px * rng.normal();
    double py = (view.top_m - p.y) / m_per_px + camera.noise_px * rng.normal();
    const bool dropped = rng.unit() < camera.drop_probability;
    if (dropped) continue;
    if (camera.quantise_px) {
      px = std::round(px);
      py = std::round(py);
    }
    out.push_back({origin + to_ns(t), view.left_m + px * m_per_px, view.top_m - py * m_per_px});
  }
  return out;
}

//! A camera's own stream for one shape: the same for the same seed, shape and rate,
//! whatever else the corpus holds.
Rng own_stream(std::uint32_t seed, int shape, const CameraModel& camera) {
  std::seed_seq seeds{seed, static_cast<std::uint32_t>(shape),
                      static_cast<std::uint32_t>(std::llround(camera.rate_hz * 1000.0))};
  return Rng(seeds);
}

}  // namespace

std::vector<Stroke> make_stroke_corpus(const Scene& scene, const CorpusConfig& config) {
  std::vector<Stroke> corpus;
  if (scene.targets.empty()) return corpus;
  const std::vector<ContactZone> zones = contact_zones(scene);
  Rng rng(config.seed);
  int shape = 0;
  for (int i = 0; i < config.shapes_per_kind; ++i) {
    for (int k = 0; k < kStrokeKinds; ++k, ++shape) {
      const auto kind = static_cast<StrokeKind>(k);
      const Path path = make_path(kind, scene, rng);
      // A clock that has run a while and is not a whole number of periods.
      const Nanos origin = 3'600 * kNanosPerSecond + to_ns(rng.uniform(0.0, 1.0));
      Stroke truth;
      truth.kind = kind;
      truth.shape = shape;
      truth.peak_speed_m_per_s = path.peak_speed();
      find_truth(path, zones, origin, truth);
      for (const CameraModel& camera : config.cameras) {
        Stroke s = truth;
        s.camera = camera.name;
        s.rate_hz = camera.rate_hz;
        if (camera.own_stream) {
          Rng own = own_stream(config.seed, shape, camera);
          s.samples = observe(path, origin, camera, scene, own);
        } else {
          s.samples = observe(path, origin, camera, scene, rng);
        }
        corpus.push_back(std::move(s));
      }
    }
  }
  return corpus;
}

}  // namespace mallet
