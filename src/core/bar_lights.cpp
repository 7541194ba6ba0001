#include "core/bar_lights.hpp"

namespace mallet {

int bar_under(const Scene& scene, Vec2 mallet_centre) {
  if (scene.kind != SceneKind::percussion) return -1;
  // As the contact solver sees the bars: each reaches a mallet radius beyond its edges, and
  // where two such reaches overlap the nearer bar has it.
  const double r = scene.mallet_radius_m, x = mallet_centre.x, lowest = mallet_centre.y - r;
  int best = -1;
  double best_distance = r;
  for (const Target& t : scene.targets) {
    const double distance = x < t.x_min ? t.x_min - x : x > t.x_max ? x - t.x_max : 0.0;
    if (distance <= best_distance && lowest >= t.top_y - 1e-9 && lowest <= t.top_y + kHoverHeightM) {
      best = t.id;
      best_distance = distance;
    }
  }
  return best;
}

BarLights bar_lights(const Scene& scene, Vec2 mallet_centre, const VisualVibration& vibration,
                                   Nanos present) {
  BarLights out{};
  if (const int hovered = bar_under(scene, mallet_centre); hovered >= 0) out[0] = {hovered, kHoverGlow};
  const double glow = vibration.glow(present);
  if (scene.kind == SceneKind::percussion && vibration.target() >= 0 && glow > 1.0 / 255)
    out[1] = {vibration.target(), static_cast<float>(glow)};
  return out;
}

}  // namespace mallet
