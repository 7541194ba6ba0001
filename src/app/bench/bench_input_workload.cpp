#include "app/bench/bench_input_workload.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <utility>

#include "core/mallet.hpp"

namespace mallet::app::input_bench {

namespace {

Observed observe(const TruePath& path, const Camera& cam, Nanos t_first, Nanos t_last, std::mt19937_64& rng,
                 TrackerTally& tally) {
  std::normal_distribution<double> noise(0.0, kNoisePx);
  IrTracker tracker;
  Observed o;
  std::optional<Vec2> prev_px;
  for (Nanos t = t_first; t <= t_last; t += kFrame) {
    const Vec2 w = path.at(t);
    const Vec2 px = cam.to_px(w);
    if (prev_px) tally.max_px_per_s = std::max(tally.max_px_per_s, std::hypot(px.x - prev_px->x, px.y - prev_px->y) / 0.01);
    prev_px = px;
    const int qx = std::clamp(static_cast<int>(std::lround(px.x + noise(rng))), 0, 1023);
    const int qy = std::clamp(static_cast<int>(std::lround(px.y + noise(rng))), 0, 767);
    IrFrame f{t, {}};
    f.slots[0] = kReflection;
    f.slots[1] = IrDot{qx, qy, 4};
    const IrTrackerUpdate u = tracker.update(f);
    if (!u.point) continue;
    o.t.push_back(t);
    o.raw.push_back(cam.to_world(u.point->x, u.point->y));
    o.truth.push_back(w);
  }
  const IrTracker::Counters& c = tracker.counters();
  tally.frames += c.frames;
  tally.accepted += c.accepted;
  tally.rejected += c.rejected_jumps;
  tally.jumps += c.jumps_followed;
  tally.lost += c.lost;
  return o;
}

}  // namespace

Workload make_workload(const Scene& scene, std::uint64_t seed, int strikes_per_track, int still_tracks) {
  Workload w(scene);
  const Camera& cam = w.cam;
  std::mt19937_64 rng(seed);
  TrackerTally& tally = w.tally;
  std::vector<Observed>& still = w.still;
  std::uint64_t& resting_strikes = w.resting_strikes;
  std::uint64_t& resting_frames = w.resting_frames;
  std::vector<StrikeTrack>& tracks = w.tracks;
  std::vector<StrikeTrack>& slow = w.slow;
  const double (&speeds)[4] = kStrikeSpeeds;
  // (a) A still hand: 12 places × 10 s.
  std::uniform_real_distribution<double> ux(-0.3, 0.3), uy(0.05, 0.3);
  for (int k = 0; k < still_tracks; ++k) {
    const Vec2 p{ux(rng), uy(rng)};
    TruePath path{{{0, p.x, p.y}, {20 * kNanosPerSecond, p.x, p.y}}};
    still.push_back(observe(path, cam, 0, 10 * kNanosPerSecond, rng, tally));
  }
  // A still hand resting exactly on each bar's contact plane, 10 s each: the raw track's
  // noise must not make strikes (the solver's re-arm hysteresis is what prevents them).
  for (const Target& bar : scene.targets) {
    const Vec2 p{0.5 * (bar.x_min + bar.x_max), bar.top_y + scene.mallet_radius_m};
    TruePath path{{{0, p.x, p.y}, {20 * kNanosPerSecond, p.x, p.y}}};
    const Observed o = observe(path, cam, 0, 10 * kNanosPerSecond, rng, tally);
    Mallet m(scene, ContactConfig{});
    for (std::size_t i = 0; i < o.t.size(); ++i) {
      const bool strike = m.update(o.t[i], o.raw[i]).has_value();
      if (o.t[i] < kNanosPerSecond) continue;  // the first touch of the plane is a (faint) strike
      resting_strikes += strike ? 1 : 0;
      ++resting_frames;
    }
  }
  // (b) Fast strikes: 4 tracks (1, 2, 3, 4 m/s ± 0.5) of random bars, 1.2 s apart.
  std::uniform_int_distribution<int> bar(0, int(scene.targets.size()) - 1);
  std::uniform_int_distribution<Nanos> phase(0, kFrame - 1);
  GhostPlayerStyle style;
  style.follow_through_m = kFollowThroughM;
  for (double v0 : speeds) {
    std::uniform_real_distribution<double> uv(std::max(1.0, v0 - 0.5), std::min(4.0, v0 + 0.5));
    StrikeTrack tr;
    for (int i = 0; i < strikes_per_track; ++i)
      tr.strikes.push_back({bar(rng), kNanosPerSecond + i * 1'200'000'000LL, uv(rng)});
    GhostPath g = ghost_player(scene, tr.strikes, kTruthRateHz, style);
    tr.path.s = std::move(g.samples);
    tr.contacts = std::move(g.contacts);
    tr.obs = observe(tr.path, cam, tr.path.s.front().t_ns + phase(rng), tr.path.s.back().t_ns, rng, tally);
    for (std::size_t i = 0; i < tr.obs.t.size(); ++i)
      if (tr.path.speed(tr.obs.t[i]) > 0.3) tr.moving.push_back(i);
    tracks.push_back(std::move(tr));
  }

  // (c) Aiming: a hand circling slowly (radius 2 cm, 0.4 Hz ≈ 5 cm/s), 4 × 10 s.
  for (int k = 0; k < 4; ++k) {
    const Vec2 c{ux(rng), uy(rng)};
    StrikeTrack tr;
    for (Nanos t = 0; t <= 11 * kNanosPerSecond; t += 1'000'000) {
      const double a = 2 * 3.141592653589793 * 0.4 * to_seconds(t);
      tr.path.s.push_back({t, c.x + 0.02 * std::cos(a), c.y + 0.02 * std::sin(a)});
    }
    tr.obs = observe(tr.path, cam, phase(rng), 10 * kNanosPerSecond, rng, tally);
    for (std::size_t i = 0; i < tr.obs.t.size(); ++i)
      if (tr.obs.t[i] >= 2 * kNanosPerSecond) tr.moving.push_back(i);
    slow.push_back(std::move(tr));
  }

  return w;
}

}  // namespace mallet::app::input_bench
