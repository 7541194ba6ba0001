#pragma once
// The Speed technique of pseudo-haptic textures (Lécuyer, Burkhardt & Etienne, "Feeling
// bumps and holes without a haptic interface", CHI 2004): the control/display gain follows
// the slope of the relief along the motion, so the cursor slows down going up and speeds
// up going down, and the visitor feels the bump or the hole.
//
// THE LAW WE IMPLEMENT. The CHI paper states the effect qualitatively (deceleration on a
// positive slope, acceleration on a negative one); we use the simplest law with that
// effect, linear in the slope along the motion:
//
//     g = clamp(1 − k · (∇h(c) · û), g_min, g_max)        c ← c + g · Δhand
//
// with c the cursor, û the unit direction of the hand's displacement Δhand, ∇h the relief's
// slope at the cursor (dimensionless, core/texture_relief.hpp) and k = `slope_gain`.
// Long displacements are integrated in sub-steps of at most R/32 so the slope is sampled
// finely whatever the pointer rate.
//
// WHY THE CURSOR AND THE HAND DO NOT DRIFT APART. Unclamped, the law is exact in one
// respect: along a straight crossing ∫ g ds = L − k·Δh, and Δh = 0 once the cursor is off
// the disc again, so a full crossing leaves (to first order in the step) no offset. What
// is left (second order, clamping, crossings that end on the disc) is removed outside the
// texture: there the offset o = c − hand relaxes towards 0 by the factor
// e^(−|Δhand| / relax_distance) per displacement — only while the hand moves, so a still
// hand sees a still cursor. Finally |o| never exceeds `max_offset`. Hence |o| is bounded
// by max_offset at all times and returns to ~0 within a few relax_distance of flat motion.
#include "core/geometry.hpp"
#include "core/texture_relief.hpp"

namespace mallet {

struct SpeedTechniqueConfig {
  double slope_gain = 2.0;          //!< k: how strongly the slope changes the gain
  double gain_min = 0.25;           //!< g never below (climbing a steep slope)
  double gain_max = 2.0;            //!< g never above (descending)
  double relax_distance_m = 0.03;   //!< hand travel over which the offset falls by 1/e off the disc
  double max_offset_m = 0.04;       //!< hard bound on |cursor − hand|
};

class SpeedTechnique {
 public:
  SpeedTechnique(const TextureRelief& relief, SpeedTechniqueConfig config);

  //! Moves the hand to `hand`; returns the displayed cursor. The first call (or the first
  //! after reset) places the cursor on the hand.
  Vec2 update(Vec2 hand);
  void reset() { started_ = false; }

  Vec2 cursor() const { return cursor_; }
  Vec2 offset() const { return {cursor_.x - hand_.x, cursor_.y - hand_.y}; }
  //! The gain of the last displacement (cursor travel / hand travel), 1 at rest.
  double gain() const { return gain_; }
  //! The law's gain for a motion in direction `dir` (any length > 0) at `cursor`.
  double gain_at(Vec2 cursor, Vec2 dir) const;

  const SpeedTechniqueConfig& config() const { return config_; }

 private:
  TextureRelief relief_;
  SpeedTechniqueConfig config_;
  bool started_ = false;
  Vec2 hand_{}, cursor_{};
  double gain_ = 1.0;
};

}  // namespace mallet
