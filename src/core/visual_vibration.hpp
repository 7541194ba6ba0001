#pragma once
// The pseudo-haptic bounce of "Virtual Chromatic Percussions" §3.2.1: at each impact the
// displayed mallet head starts to oscillate along the surface normal following Eq. 1
// with the material's *visual* triple (A in seconds, so A·v is metres).
// The displacement is evaluated from the time since the impact on the int64 clock, so
// it is the same after 30 days of uptime as after one second.
#include <algorithm>
#include <cmath>
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
    state_ = State{impact.t_ns, impact.speed_m_per_s, visual, impact.target};
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

  //! The struck bar (Target::id), -1 before any impact.
  int target() const { return state_ ? state_->target : -1; }
  //! How brightly the struck bar glows at `now`, 0..1, from a brightness set by the strike's
  //! speed (full at 2 m/s and above, a quarter at the softest) times glow_of_envelope() of
  //! Eq. 1's envelope e^(−B·t) with the material's visual B. 0 before the impact and without
  //! one.
  double glow(Nanos now) const {
    if (!state_ || now < state_->t0) return 0.0;
    const double brightness = std::clamp(state_->speed / 2.0, 0.25, 1.0);
    return brightness * glow_of_envelope(std::exp(-state_->params.decay_per_s * to_seconds(now - state_->t0)));
  }

  //! The envelope below which the glow is out: 1/256, one step of 8-bit colour (−48 dB).
  static constexpr double kGlowEnvelopeFloor = 1.0 / 256;
  //! The glow for an envelope value e (1 at the strike, falling to 0), 0..1: a flash, e
  //! itself, over a tail, e in decibels from the peak (0 dB → 1) to kGlowEnvelopeFloor
  //! (→ 0), half of each. Eyes (like ears) judge a fading light by ratios, not differences:
  //! e itself drops below a tenth of the peak within 0.26–0.29 s at the shipped B (8–9/s)
  //! and reads as a blink; its level in dB falls linearly in time and is still half at
  //! 0.3 s. Both are functions of e alone, so the glow keeps Eq. 1's timing: a larger B
  //! fades it sooner, in proportion, and it is out where the envelope is.
  static double glow_of_envelope(double e) {
    if (!(e > kGlowEnvelopeFloor)) return 0.0;
    const double level = 1.0 - std::log(std::min(e, 1.0)) / std::log(kGlowEnvelopeFloor);
    return 0.5 * std::min(e, 1.0) + 0.5 * level;
  }

 private:
  struct State {
    Nanos t0;
    double speed;
    VibrationParams params;
    int target;
  };
  BounceMode mode_;
  std::optional<State> state_;
};

}  // namespace mallet
