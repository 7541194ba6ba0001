#include "core/scene_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mallet {

namespace {

struct Span {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double a, double b) {
    lo = std::min(lo, a);
    hi = std::max(hi, b);
  }
  bool empty() const { return !(hi >= lo); }
  double width() const { return hi - lo; }
  double centre() const { return 0.5 * (lo + hi); }
};

//! How large `content` is shown on a screen of `aspect`: screen heights per metre.
double shown_scale(const ScreenToWorld& content, double aspect) {
  return std::min(aspect / content.width_m(), 1.0 / content.height_m());
}

//! The content narrowed to `span` plus `margin` each side, never wider than it was; false
//! when it stays as it was.
bool narrow_to(ScreenToWorld& content, Span span, double margin) {
  if (span.empty() || span.width() + 2 * margin >= content.width_m()) return false;
  content.left_m = span.lo - margin;
  content.right_m = span.hi + margin;
  return true;
}

}  // namespace

Scene portrait_layout(const Scene& scene) {
  Scene out = scene;
  out.layout = SceneLayout::portrait;
  const ScreenToWorld& content = scene.screen_to_world;
  const double rows_apart = content.height_m();
  const double margin = rows_apart / 8;
  const double centre_x = 0.5 * (content.left_m + content.right_m);
  bool narrowed = false;
  if (scene.kind == SceneKind::texture && scene.texture) {
    const TextureRelief& relief = scene.texture->relief;
    Span disc;
    disc.add(relief.center.x - relief.radius_m, relief.center.x + relief.radius_m);
    narrowed = narrow_to(out.screen_to_world, disc, margin);
  } else if (scene.kind == SceneKind::percussion && scene.instruments.size() >= 2) {
    double widest = 0;
    int row = 0;
    for (const Instrument& inst : scene.instruments) {
      Span bars;
      for (int id : inst.targets) {
        const Target& t = scene.targets.at(static_cast<std::size_t>(id));
        bars.add(t.x_min, t.x_max);
      }
      if (bars.empty()) continue;
      const double dx = centre_x - bars.centre(), dy = -rows_apart * row++;
      for (int id : inst.targets) {
        Target& t = out.targets.at(static_cast<std::size_t>(id));
        t.x_min += dx;
        t.x_max += dx;
        t.top_y += dy;
      }
      widest = std::max(widest, bars.width());
    }
    Span all;
    all.add(centre_x - widest / 2, centre_x + widest / 2);
    narrowed = narrow_to(out.screen_to_world, all, margin);
    out.screen_to_world.bottom_m = content.bottom_m - rows_apart * std::max(row - 1, 0);
    out.camera.eye_y_m = scene.camera.eye_y_m - rows_apart * std::max(row - 1, 0) / 2;
  } else {
    Span bars;
    for (const Target& t : scene.targets) bars.add(t.x_min, t.x_max);
    narrowed = narrow_to(out.screen_to_world, bars, margin);
  }
  // The eye faces the narrowed content's middle (the rows are centred on it).
  if (narrowed) out.camera.eye_x_m = 0.5 * (out.screen_to_world.left_m + out.screen_to_world.right_m);
  return out;
}

SceneLayout layout_for(const Scene& scene, double aspect) {
  if (!(aspect > 0) || !std::isfinite(aspect) || aspect >= 1) return SceneLayout::landscape;
  const Scene portrait = portrait_layout(scene);
  return shown_scale(portrait.screen_to_world, aspect) > 1.01 * shown_scale(scene.screen_to_world, aspect)
             ? SceneLayout::portrait
             : SceneLayout::landscape;
}

Scene laid_out(const Scene& scene, SceneLayout layout) {
  return layout == SceneLayout::portrait ? portrait_layout(scene) : scene;
}

Vec2 to_layout(const Scene& file_scene, const Scene& laid, Vec2 world) {
  double best = std::numeric_limits<double>::infinity();
  Vec2 moved = world;
  for (const Instrument& inst : file_scene.instruments) {
    Span bars;
    for (int id : inst.targets) {
      const Target& t = file_scene.targets.at(static_cast<std::size_t>(id));
      bars.add(t.x_min, t.x_max);
    }
    if (bars.empty() || inst.targets.front() >= static_cast<int>(laid.targets.size())) continue;
    const double away = world.x < bars.lo ? bars.lo - world.x : world.x > bars.hi ? world.x - bars.hi : 0.0;
    if (away >= best) continue;
    best = away;
    const Target& was = file_scene.targets.at(static_cast<std::size_t>(inst.targets.front()));
    const Target& now = laid.targets.at(static_cast<std::size_t>(inst.targets.front()));
    moved = {world.x + (now.x_min - was.x_min), world.y + (now.top_y - was.top_y)};
  }
  return moved;
}

}  // namespace mallet
