#pragma once
// The texture scene's cursor, as the kiosk and `mallet simulate` both run it: the hand
// drives the Speed technique, and each sample gives the stripes their motion update —
// the displayed cursor's speed over the segment that ends at this sample (so the
// stripes follow the cursor one pointer period late, causally), and whether the cursor
// is over the disc.
#include <cmath>

#include "core/scene.hpp"

namespace mallet {

class TextureCursor {
 public:
  explicit TextureCursor(const TextureStimulus& texture)
      : relief_(texture.relief), speed_(texture.relief, texture.speed) {}

  StripeMotion update(Nanos t, Vec2 hand) {
    const Vec2 c = speed_.update(hand);
    StripeMotion m{t, 0.0, relief_.covers(c)};
    if (have_last_ && t > last_t_)
      m.speed_m_per_s = std::hypot(c.x - last_.x, c.y - last_.y) / (static_cast<double>(t - last_t_) * 1e-9);
    have_last_ = true;
    last_t_ = t;
    last_ = c;
    return m;
  }
  void reset() {
    speed_.reset();
    have_last_ = false;
  }
  Vec2 cursor() const { return speed_.cursor(); }
  double gain() const { return speed_.gain(); }

 private:
  TextureRelief relief_;
  SpeedTechnique speed_;
  Nanos last_t_ = 0;
  Vec2 last_{};
  bool have_last_ = false;
};

}  // namespace mallet
