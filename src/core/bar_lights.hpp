#pragma once
// What the bars show a visitor besides themselves: the bar about to be struck, lit softly
// while the mallet hovers over it, and the bar just struck, glowing and fading with its
// material's visual decay (VisualVibration::glow). Per frame, like the bounce: the
// renderer redraws those bars over its cached background with the light added.
#include <array>
#include <cstddef>

#include "core/geometry.hpp"
#include "core/scene.hpp"
#include "core/time.hpp"
#include "core/visual_vibration.hpp"

namespace mallet {

struct BarLight {
  int target = -1;   //!< Target::id; -1: none
  float glow = 0;    //!< 0..1
};

//! How brightly the bar under the hovering mallet is lit: subtle, a hint, not a strike.
inline constexpr float kHoverGlow = 0.2f;
//! How far above a bar's top the mallet's lowest point may hover for the bar to be lit.
inline constexpr double kHoverHeightM = 0.12;

//! The bar the mallet hovers over, the one it would strike: its centre within a mallet
//! radius of the bar's span (the nearer bar where two are), its lowest point above the
//! bar's top by at most kHoverHeightM; -1 when none (or not a percussion scene).
int bar_under(const Scene& scene, Vec2 mallet_centre);

//! How brightly a bar the screen points a visitor to is lit, steadily: the study offer's
//! "Yes" among bars the ghost keeps striking (brighter than a hover, dimmer than a strike).
inline constexpr float kCalledOutGlow = 0.45f;

//! The lights a frame may show: [0] the bar under the mallet, [1] the bar last struck, [2]
//! a bar the screen points a visitor to (the caller's: -1 from bar_lights()).
inline constexpr std::size_t kBarLights = 3;
using BarLights = std::array<BarLight, kBarLights>;

//! [0] the bar under the mallet (kHoverGlow), [1] the bar last struck (its glow at
//! `present`, when above 1/255); [2] none.
BarLights bar_lights(const Scene& scene, Vec2 mallet_centre, const VisualVibration& vibration,
                                   Nanos present);

}  // namespace mallet
