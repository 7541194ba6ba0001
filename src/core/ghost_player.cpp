#include "core/ghost_player.hpp"

#include <algorithm>
#include <cmath>

#include "core/geometry.hpp"

namespace mallet {

namespace {

struct Waypoint {
  Nanos t;
  Vec2 p;
};

Nanos seconds_ns(double s) { return static_cast<Nanos>(std::llround(s * 1e9)); }

}  // namespace

GhostPath ghost_player(const Scene& scene, const std::vector<ScriptedStrike>& strikes, double rate_hz,
                       const GhostPlayerStyle& style) {
  GhostPath out;
  if (strikes.empty() || !(rate_hz > 0)) return out;
  const double r = scene.mallet_radius_m;
  std::vector<Waypoint> path;
  for (const ScriptedStrike& s : strikes) {
    const Target& bar = scene.targets.at(static_cast<std::size_t>(s.target));
    const double x = 0.5 * (bar.x_min + bar.x_max);
    const double plane = bar.top_y + r;
    const double v = std::max(s.speed_m_per_s, 1e-3);
    // The approach lasts at least two sample intervals, like the follow-through below.
    const double approach = std::max(style.hover_height_m, 2.0 * v / rate_hz);
    const double hover = plane + approach;
    const Nanos down = seconds_ns(approach / v);
    Nanos start = s.t_ns - down;
    if (!path.empty()) {
      // Travel at hover height from the previous lift to above this bar, at 1 m/s.
      const Waypoint prev = path.back();
      const Nanos arrive = prev.t + seconds_ns(std::hypot(x - prev.p.x, hover - prev.p.y));
      if (start < arrive) start = arrive;  // late: strike as soon as it arrives
      if (start > arrive) path.push_back({arrive, {x, hover}});
    }
    path.push_back({start, {x, hover}});
    const Nanos contact = start + down;
    out.contacts.push_back(contact);
    // The follow-through lasts at least two sample intervals, so the samples on both
    // sides of the contact lie on the straight descent: its time and speed are exact.
    const double depth = std::max(style.follow_through_m, 2.0 * v / rate_hz);
    const Nanos bottom = contact + seconds_ns(depth / v);
    path.push_back({bottom, {x, plane - depth}});
    const Nanos lifted = bottom + seconds_ns((approach + depth) / style.lift_speed_m_per_s);
    path.push_back({lifted, {x, hover}});
  }
  const Nanos t0 = path.front().t;
  std::size_t seg = 0;
  for (Nanos k = 0;; ++k) {
    const Nanos t = t0 + seconds_ns(static_cast<double>(k) / rate_hz);
    if (t > path.back().t) break;
    while (seg + 1 < path.size() && path[seg + 1].t < t) ++seg;
    const Waypoint& a = path[seg];
    const Waypoint& b = path[std::min(seg + 1, path.size() - 1)];
    const double s = b.t > a.t ? static_cast<double>(t - a.t) / static_cast<double>(b.t - a.t) : 1.0;
    const Vec2 p = lerp(a.p, b.p, std::clamp(s, 0.0, 1.0));
    out.samples.push_back({t, p.x, p.y});
  }
  return out;
}

}  // namespace mallet
