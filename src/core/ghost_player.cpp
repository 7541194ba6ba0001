#include "core/ghost_player.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/geometry.hpp"
#include "core/mallet.hpp"

namespace mallet {

namespace {

struct Waypoint {
  Nanos t;
  Vec2 p;
};

Nanos seconds_ns(double s) { return static_cast<Nanos>(std::llround(s * 1e9)); }

//! The segment a–b meets the box [x0, x1] × [y0, y1].
bool meets_box(Vec2 a, Vec2 b, double x0, double x1, double y0, double y1) {
  double s0 = 0, s1 = 1;  // Liang–Barsky: the part of the segment inside each slab
  const double d[2] = {b.x - a.x, b.y - a.y}, p[2] = {a.x, a.y}, lo[2] = {x0, y0}, hi[2] = {x1, y1};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (p[k] < lo[k] || p[k] > hi[k]) return false;
      continue;
    }
    double e0 = (lo[k] - p[k]) / d[k], e1 = (hi[k] - p[k]) / d[k];
    if (e0 > e1) std::swap(e0, e1);
    s0 = std::max(s0, e0);
    s1 = std::min(s1, e1);
  }
  return s0 <= s1;
}

//! The travel from `from` to `to` around the rows of bars it would pass through (stacked
//! instruments: the bars of an upper row have a finite floor, core/mallet.hpp): the waypoints
//! before `to`, beside the end of each such row that is nearer the way.
std::vector<Vec2> around_rows(const std::vector<ContactZone>& zones, Vec2 from, Vec2 to, double clearance) {
  std::vector<Vec2> via;
  Vec2 at = from;
  for (std::size_t guard = 0; guard < zones.size(); ++guard) {
    const ContactZone* blocking = nullptr;
    for (const ContactZone& z : zones)
      if (std::isfinite(z.floor_y) && meets_box(at, to, z.lo, z.hi, z.floor_y - clearance, z.plane_y + clearance))
        blocking = &z;
    if (!blocking) break;
    double lo = blocking->lo, hi = blocking->hi;  // its whole row
    for (const ContactZone& z : zones)
      if (z.plane_y == blocking->plane_y) {
        lo = std::min(lo, z.lo);
        hi = std::max(hi, z.hi);
      }
    const double left = lo - clearance, right = hi + clearance;
    const double side = std::fabs(at.x - left) + std::fabs(to.x - left) < std::fabs(at.x - right) + std::fabs(to.x - right)
                            ? left
                            : right;
    via.push_back({side, at.y});
    via.push_back({side, to.y});
    at = via.back();
  }
  return via;
}

}  // namespace

GhostPath ghost_player(const Scene& scene, const std::vector<ScriptedStrike>& strikes, double rate_hz,
                       const GhostPlayerStyle& style) {
  GhostPath out;
  if (strikes.empty() || !(rate_hz > 0)) return out;
  const double r = scene.mallet_radius_m;
  const std::vector<ContactZone> zones = contact_zones(scene);
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
      // Travel at hover height from the previous lift to above this bar, at 1 m/s, around
      // the rows of bars on the way (stacked instruments).
      Waypoint prev = path.back();
      for (const Vec2 p : around_rows(zones, prev.p, {x, hover}, 2 * r)) {
        prev = {prev.t + seconds_ns(std::hypot(p.x - prev.p.x, p.y - prev.p.y)), p};
        path.push_back(prev);
      }
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
