#include "core/speed_technique.hpp"

#include <algorithm>
#include <cmath>

namespace mallet {

SpeedTechnique::SpeedTechnique(const TextureRelief& relief, SpeedTechniqueConfig config)
    : relief_(relief), config_(config) {}

double SpeedTechnique::gain_at(Vec2 cursor, Vec2 dir) const {
  const double len = std::hypot(dir.x, dir.y);
  if (!(len > 0)) return 1.0;
  const Vec2 g = relief_.gradient_at(cursor);
  const double slope = (g.x * dir.x + g.y * dir.y) / len;
  return std::clamp(1.0 - config_.slope_gain * slope, config_.gain_min, config_.gain_max);
}

Vec2 SpeedTechnique::update(Vec2 hand) {
  if (!std::isfinite(hand.x) || !std::isfinite(hand.y)) return cursor_;
  if (!started_) {
    started_ = true;
    hand_ = cursor_ = hand;
    gain_ = 1.0;
    return cursor_;
  }
  const Vec2 d{hand.x - hand_.x, hand.y - hand_.y};
  const double dist = std::hypot(d.x, d.y);
  if (dist == 0.0) {
    gain_ = 1.0;
    return cursor_;
  }
  const double max_step = relief_.radius_m / 32;
  const int steps = static_cast<int>(std::min(1e6, std::ceil(dist / max_step)));
  const Vec2 step{d.x / steps, d.y / steps};
  const double step_len = dist / steps;
  double travelled = 0;
  Vec2 c = cursor_;
  for (int i = 0; i < steps; ++i) {
    // The slope at the middle of the sub-step the cursor is about to make (midpoint rule).
    const double g0 = gain_at(c, d);
    const Vec2 mid{c.x + step.x * g0 / 2, c.y + step.y * g0 / 2};
    const double g = gain_at(mid, d);
    c = {c.x + step.x * g, c.y + step.y * g};
    travelled += g * step_len;
    Vec2 h{hand_.x + step.x * (i + 1), hand_.y + step.y * (i + 1)};
    if (!relief_.covers(c)) {  // off the texture: the offset relaxes towards the hand
      const double k = std::exp(-step_len / config_.relax_distance_m);
      c = {h.x + (c.x - h.x) * k, h.y + (c.y - h.y) * k};
    }
  }
  hand_ = hand;
  Vec2 o{c.x - hand.x, c.y - hand.y};
  const double olen = std::hypot(o.x, o.y);
  if (olen > config_.max_offset_m) {
    const double s = config_.max_offset_m / olen;
    o = {o.x * s, o.y * s};
  }
  cursor_ = {hand.x + o.x, hand.y + o.y};
  gain_ = travelled / dist;
  return cursor_;
}

}  // namespace mallet
