#pragma once
// The relief of the second paper's texture scene: a bump or a hole under a white disc,
// seen from above (Lécuyer et al., CHI 2004: the screen shows a top view, the relief is
// felt through the cursor's speed). Heights are metres along the viewer's axis; the
// slope ∇h is dimensionless. Outside the disc the surface is flat (h = 0, ∇h = 0), and
// both profiles reach 0 at the rim with no step.
//
//   cosine:    h(r) = s·H·(1 + cos(π·r/R)) / 2                       r < R
//   gaussian:  h(r) = s·H·(e^(−r²/2σ²) − e^(−R²/2σ²)) / (1 − e^(−R²/2σ²)),  σ = R/3
//
// with s = +1 for a bump, −1 for a hole, R the disc's radius and H its height (> 0).
#include <string>

#include "core/enum_names.hpp"
#include "core/geometry.hpp"

namespace mallet {

enum class ReliefShape { bump, hole };
enum class ReliefProfile { gaussian, cosine };
inline constexpr EnumNames<ReliefShape, 2> kReliefShapeNames{
    {{ReliefShape::bump, "bump"}, {ReliefShape::hole, "hole"}}};
inline constexpr EnumNames<ReliefProfile, 2> kReliefProfileNames{
    {{ReliefProfile::gaussian, "gaussian"}, {ReliefProfile::cosine, "cosine"}}};

struct TextureRelief {
  ReliefShape shape = ReliefShape::bump;
  ReliefProfile profile = ReliefProfile::gaussian;
  Vec2 center{0.0, 0.0};   //!< world metres
  double radius_m = 0.06;  //!< R: the white disc
  double height_m = 0.01;  //!< H: the bump's height or the hole's depth (> 0)

  double height_at(Vec2 p) const;   //!< h(p), metres
  Vec2 gradient_at(Vec2 p) const;   //!< ∇h(p), dimensionless
  bool covers(Vec2 p) const;        //!< inside the disc (r < R)
};

const char* to_string(ReliefShape s);
const char* to_string(ReliefProfile p);

}  // namespace mallet
