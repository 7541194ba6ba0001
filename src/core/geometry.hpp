#pragma once
// World space: metres, y up. The mallet moves in the vertical plane of the paper's
// Figure 8: x along the instruments, y the height above the bars.

namespace mallet {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Vec2&, const Vec2&) = default;
};

inline Vec2 lerp(Vec2 a, Vec2 b, double s) { return {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s}; }

}  // namespace mallet
