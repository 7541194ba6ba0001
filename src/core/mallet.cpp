#include "core/mallet.hpp"

#include <algorithm>
#include <cmath>

namespace mallet {

std::vector<ContactZone> contact_zones(const Scene& scene) {
  const double r = scene.mallet_radius_m;
  std::vector<ContactZone> zones;
  for (const Target& t : scene.targets)
    zones.push_back({t.id, t.x_min - r, t.x_max + r, false, t.top_y + r});
  // Cut overlapping zones of equal height at the middle of the gap between the bars.
  for (ContactZone& a : zones) {
    for (ContactZone& b : zones) {
      if (&a == &b || a.plane_y != b.plane_y) continue;
      const Target& ta = scene.targets[a.target];
      const Target& tb = scene.targets[b.target];
      if (ta.x_max <= tb.x_min && a.hi > b.lo) {  // a left of b, zones overlap
        // Only ever narrow a zone: with a large head, bars two apart overlap too, and
        // their cut must not undo the cut between neighbours (each x keeps its nearest bar).
        const double mid = 0.5 * (ta.x_max + tb.x_min);
        if (mid <= a.hi) {
          a.hi = mid;
          a.hi_open = true;  // the cut itself belongs to the bar on the right
        }
        b.lo = std::max(b.lo, mid);
      }
    }
  }
  // A bar higher than another (stacked instruments) holds only through itself: the space
  // below it, beside the lower instrument's ends too, is the lower instrument's to swing in.
  for (ContactZone& a : zones)
    for (const ContactZone& b : zones)
      if (b.plane_y < a.plane_y) {
        const Target& t = scene.targets[a.target];
        a.floor_y = t.top_y - t.thickness_m - r;
        break;
      }
  return zones;
}

const ContactZone* zone_at(const std::vector<ContactZone>& zones, Vec2 c) {
  const ContactZone* best = nullptr;
  for (const ContactZone& z : zones)
    if (z.contains(c.x) && c.y >= z.floor_y && (!best || z.plane_y > best->plane_y)) best = &z;
  return best;
}

Mallet::Mallet(const Scene& scene, ContactConfig config)
    : scene_(&scene), config_(config), zones_(contact_zones(scene)) {
  for (const Target& t : scene.targets) materials_.push_back(t.material);
}

void Mallet::set_material(int target, int material) {
  if (target >= 0 && static_cast<std::size_t>(target) < materials_.size() && material >= 0 &&
      static_cast<std::size_t>(material) < scene_->materials.size())
    materials_[static_cast<std::size_t>(target)] = material;
}

int Mallet::material_of(int target) const { return materials_.at(static_cast<std::size_t>(target)); }

void Mallet::reset() { last_.reset(); }

void Mallet::disarm(const ContactZone& zone, double hand_y) {
  armed_ = false;
  rearm_y_ = std::max(hand_y, zone.plane_y) + config_.rearm_height_m;
  rearm_floor_y_ = zone.floor_y;
}

Impact Mallet::impact_on(const ContactZone& zone, Nanos t_ns, double speed_m_per_s, double x_m) const {
  const Target& target = scene_->targets[static_cast<std::size_t>(zone.target)];
  Impact out;
  out.t_ns = t_ns;
  out.target = target.id;
  out.material = materials_[static_cast<std::size_t>(target.id)];
  out.note = target.note;
  out.speed_m_per_s = speed_m_per_s;
  out.x_m = x_m;
  return out;
}

Vec2 Mallet::displayed_centre(Vec2 hand) const {
  const ContactZone* z = zone_at(hand);
  if (z && hand.y < z->plane_y) return {hand.x, z->rest_y(hand.y)};
  return hand;
}

std::optional<Impact> Mallet::update(Nanos t_ns, Vec2 hand) {
  if (!std::isfinite(hand.x) || !std::isfinite(hand.y)) {
    ++counters_.ignored_non_finite;
    return std::nullopt;
  }
  if (last_ && t_ns <= last_->t_ns) {
    ++counters_.ignored_not_after_previous;
    return std::nullopt;
  }
  ++counters_.accepted;

  std::optional<Impact> impact;
  if (last_ && armed_) {
    const Vec2 a = last_->hand;
    const Nanos dt = t_ns - last_->t_ns;
    // Earliest downward crossing of a contact plane inside its zone.
    const ContactZone* hit = nullptr;
    double hit_s = 2.0;
    for (const ContactZone& z : zones_) {
      if (!(a.y > z.plane_y && hand.y <= z.plane_y)) continue;
      const double s = (a.y - z.plane_y) / (a.y - hand.y);
      const double x = a.x + (hand.x - a.x) * s;
      if (z.contains(x) && s < hit_s) {
        hit = &z;
        hit_s = s;
      }
    }
    if (hit) {
      armed_ = false;
      rearm_y_ = hit->plane_y + config_.rearm_height_m;
      rearm_floor_y_ = hit->floor_y;
      double v = (a.y - hand.y) / to_seconds(dt);
      if (v < config_.min_impact_speed_m_per_s) {
        ++counters_.touches_below_min_speed;
      } else {
        if (v > config_.max_impact_speed_m_per_s) {
          v = config_.max_impact_speed_m_per_s;
          ++counters_.clamped_speed;
        }
        ++counters_.impacts;
        impact = impact_on(*hit, last_->t_ns + static_cast<Nanos>(std::llround(hit_s * static_cast<double>(dt))), v,
                           a.x + (hand.x - a.x) * hit_s);
      }
    }
  }

  // Any contact (a strike, a touch, a sideways entry, a first sample on a bar) disarms
  // until the hand rises clear of the plane it touched, or passes under its bar.
  if (const ContactZone* z = zone_at(hand); z && z->holds(hand)) {
    armed_ = false;
    rearm_y_ = z->plane_y + config_.rearm_height_m;
    rearm_floor_y_ = z->floor_y;
  } else if (!armed_ && (hand.y >= rearm_y_ || hand.y < rearm_floor_y_)) {
    armed_ = true;
  }
  last_ = Last{t_ns, hand};
  return impact;
}

}  // namespace mallet
