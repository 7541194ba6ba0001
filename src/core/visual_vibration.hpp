#pragma once
// The pseudo-haptic bounce of "Virtual Chromatic Percussions" §3.2.1: at each impact the
// displayed mallet head starts to oscillate along the surface normal following Eq. 1
// with the material's *visual* triple (A in seconds, so A·v is metres).
// The displacement is evaluated from the time since the impact on the int64 clock, so
// it is the same after 30 days of uptime as after one second.
#include <optional>

#include "core/impact.hpp"
#include "core/vibration.hpp"

namespace mallet {

enum class BounceMode {
  signed_eq1,  //!< Q(t) exactly as Eq. 1: the head also dips below the surface (default)
  rectified,   //!< |Q(t)|: the head only bounces away from the surface
};

class VisualVibration {
 public:
  explicit VisualVibration(BounceMode mode = BounceMode::signed_eq1) : mode_(mode) {}

  //! A new impact restarts the bounce (the latest strike is the one the eye follows).
  void start(const Impact& impact, const VibrationParams& visual) {
    state_ = State{impact.t_ns, impact.speed_m_per_s, visual};
  }
  void clear() { state_.reset(); }

  //! Displacement in metres along the surface normal, positive away from the surface,
  //! at time `now` (e.g. a frame's predicted present time). 0 before the impact.
  double offset_m(Nanos now) const {
    if (!state_) return 0.0;
    const double q = eq1(state_->params, state_->speed, now - state_->t0);
    return mode_ == BounceMode::rectified ? (q < 0 ? -q : q) : q;
  }

  std::optional<Nanos> impact_time() const {
    return state_ ? std::optional<Nanos>(state_->t0) : std::nullopt;
  }

 private:
  struct State {
    Nanos t0;
    double speed;
    VibrationParams params;
  };
  BounceMode mode_;
  std::optional<State> state_;
};

}  // namespace mallet
