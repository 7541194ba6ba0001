#pragma once
// The mapping from the pointer's normalised screen coordinates (0..1, origin top-left,
// y down) to the world's vertical plane (metres, y up). It is part of the scene: the
// rectangle of the plane that must be seen (the content). A screen of other proportions
// shows more than that rectangle, never less and never stretched: framed().
#include <cmath>

#include "core/geometry.hpp"

namespace mallet {

struct ScreenToWorld {
  double left_m = -0.5;   //!< world x at screen x = 0
  double right_m = 0.5;   //!< world x at screen x = 1
  double top_m = 0.5;     //!< world y at screen y = 0
  double bottom_m = 0.0;  //!< world y at screen y = 1

  Vec2 map(double screen_x, double screen_y) const {
    return {left_m + screen_x * (right_m - left_m), top_m + screen_y * (bottom_m - top_m)};
  }
  Vec2 unmap(Vec2 world) const {
    return {(world.x - left_m) / (right_m - left_m), (world.y - top_m) / (bottom_m - top_m)};
  }
  double width_m() const { return std::fabs(right_m - left_m); }
  double height_m() const { return std::fabs(top_m - bottom_m); }
  //! Width over height: the screen proportions that show this rectangle unstretched.
  double aspect() const { return width_m() / height_m(); }
};

//! The rectangle a screen of `aspect` (its width over its height, square pixels) shows:
//! `content` grown about its centre across one direction until its proportions are the
//! screen's. A metre is then as many pixels across as up (a sphere is a circle), all of the
//! content is in view, and the rest of the screen shows more of the world around it.
//! An aspect that is not a positive finite number, or is the content's own (to 1e-9), leaves
//! `content` exactly as it is.
inline ScreenToWorld framed(const ScreenToWorld& content, double aspect) {
  if (!(aspect > 0) || !std::isfinite(aspect) || std::fabs(aspect / content.aspect() - 1) < 1e-9) return content;
  ScreenToWorld out = content;
  const double cx = (content.left_m + content.right_m) / 2, cy = (content.top_m + content.bottom_m) / 2;
  const double w = content.width_m(), h = content.height_m();
  if (aspect > content.aspect()) {  // wider: more on the left and right
    const double half = h * aspect / 2 * (content.right_m >= content.left_m ? 1 : -1);
    out.left_m = cx - half;
    out.right_m = cx + half;
  } else if (aspect < content.aspect()) {  // narrower or portrait: more above and below
    const double half = w / aspect / 2 * (content.top_m >= content.bottom_m ? 1 : -1);
    out.top_m = cy + half;
    out.bottom_m = cy - half;
  }
  return out;
}

}  // namespace mallet
