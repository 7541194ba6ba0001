#pragma once
// The mapping from the pointer's normalised screen coordinates (0..1, origin top-left,
// y down) to the world's vertical plane (metres, y up). It is part of the scene: the
// rectangle of the plane that the screen shows.
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
};

}  // namespace mallet
