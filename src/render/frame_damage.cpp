#include "render/frame_damage.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace mallet::render {

PixelRect overlay_rect(const std::vector<OverlayVertex>& vertices, int width, int height) {
  if (vertices.empty() || width <= 0 || height <= 0) return {};
  float x0 = vertices[0].x, y0 = vertices[0].y, x1 = x0, y1 = y0;
  for (const OverlayVertex& v : vertices) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y)) return {0, 0, width, height};
    x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
  }
  // A pixel of margin: a fragment is covered by its centre, and float rounding.
  auto clamp_to = [](float v, int hi) {
    return static_cast<int>(std::clamp(static_cast<double>(v), 0.0, static_cast<double>(hi)));
  };
  const PixelRect r{clamp_to(std::floor(x0) - 1, width), clamp_to(std::floor(y0) - 1, height),
                    clamp_to(std::ceil(x1) + 1, width), clamp_to(std::ceil(y1) + 1, height)};
  return r.empty() ? PixelRect{} : r;
}

namespace {

float glow_of(const FrameLook& look, int target) {
  float glow = 0;
  for (const BarLight& l : look.lights)
    if (l.target == target) glow = std::max(glow, l.glow);
  return glow;
}

PixelRect rect_of(const FrameLook& look, int target) {
  for (std::size_t i = 0; i < look.lights.size(); ++i)
    if (look.lights[i].target == target) return look.light_rects[i];
  return {};
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_mallet(const FrameLook& a, const FrameLook& b) {
  return a.mallet == b.mallet && (!a.mallet || a.mallet_px == b.mallet_px);
}

}  // namespace

PixelRect changed_between(const FrameLook& before, const FrameLook& after) {
  const PixelRect whole{0, 0, after.width, after.height};
  if (before.width != after.width || before.height != after.height || before.instruments != after.instruments)
    return whole;
  PixelRect changed;
  if (!same_mallet(before, after)) changed = bounding(before.mallet_rect, after.mallet_rect);
  for (const FrameLook* look : {&before, &after})
    for (const BarLight& l : look->lights)
      if (l.target >= 0 && glow_of(before, l.target) != glow_of(after, l.target))
        changed = bounding(changed, bounding(rect_of(before, l.target), rect_of(after, l.target)));
  static_assert(sizeof(OverlayVertex) == 8 * sizeof(float), "compared byte for byte: no padding");
  if (before.overlay_atlas != after.overlay_atlas || before.overlay_atlas_generation != after.overlay_atlas_generation ||
      !same_bytes(before.overlay_vertices, after.overlay_vertices) ||
      !same_bytes(before.overlay_indices, after.overlay_indices))
    changed = bounding(changed, bounding(overlay_rect(before.overlay_vertices, after.width, after.height),
                                         overlay_rect(after.overlay_vertices, after.width, after.height)));
  return changed;
}

FrameLook settled(const FrameLook& drawn, FrameLook next) {
  if (drawn.width != next.width || drawn.height != next.height) return next;
  // A head within kStillMalletPx of where it is drawn stays there: its drift is measured
  // from there, so it is never further behind.
  if (drawn.mallet && next.mallet && glm::length(drawn.mallet_px - next.mallet_px) < kStillMalletPx) {
    next.mallet_centre = drawn.mallet_centre;
    next.mallet_px = drawn.mallet_px;
    next.mallet_rect = drawn.mallet_rect;
  }
  for (BarLight& l : next.lights) {
    const float was = glow_of(drawn, l.target);
    if (l.target >= 0 && l.glow > 0 && was > 0 && std::abs(l.glow - was) < kStillGlow) l.glow = was;
  }
  return next;
}

bool FrameDamage::changes(const FrameLook& next) const {
  return !last_ || !changed_between(*last_, settled(*last_, next)).empty();
}

PixelRect FrameDamage::commit(FrameLook next, int age) {
  const PixelRect whole{0, 0, next.width, next.height};
  if (last_ && age > 0) next = settled(*last_, next);  // a whole frame is drawn exactly
  const PixelRect changed = last_ ? changed_between(*last_, next) : whole;
  const std::uint64_t n = frames_++;
  changed_[n % kHistory] = changed;
  last_ = std::move(next);
  if (age <= 0 || static_cast<std::uint64_t>(age) > std::min<std::uint64_t>(n, kHistory)) return whole;
  PixelRect draw;  // frames n - age + 1 .. n changed these since the image's frame, n - age
  for (std::uint64_t k = n + 1 - static_cast<std::uint64_t>(age); k <= n; ++k)
    draw = bounding(draw, changed_[k % kHistory]);
  return draw;
}

void FrameDamage::forget() {
  last_.reset();
  changed_ = {};
}

}  // namespace mallet::render
