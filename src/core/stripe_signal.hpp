#pragma once
// Vibrotactile stripes, Eq. 1 of "Pseudo-Haptic Feedback Augmented with Visual and
// Tactile Vibrations":
//
//     y(t) = A · sin(2π · ∫₀ᵗ v(τ) dτ / λ + φ)
//
// a stripe pattern of constant wavelength λ under the cursor: the cursor's speed v becomes
// the frequency v/λ. The integral is the distance the displayed cursor travelled since the
// start of the gesture, kept in double precision as (distance at the last motion update)
// + v · (time since it) — per sample nothing is accumulated, so the phase cannot drift,
// and each update adds its segment with Neumaier's compensated sum.
//
// Motion updates give the cursor's speed from then on and whether it is over the textured
// disc. A gesture starts at the first update with v > rest_speed after the signal fell
// silent (distance 0, phase φ) and lasts while the cursor keeps moving. The signal is
// silent at rest and off the disc: an envelope ramps the amplitude to 0 (and back to 1)
// over `fade_s` so neither case clicks, and once it is 0 the output is exactly 0.
// With no motion update for `motion_timeout_s` the cursor is at rest from that instant.
// Frequencies above `max_freq_hz` are held there (the actuator's band, and never near
// Nyquist) by capping the speed used for the phase.
#include <cstdint>
#include <type_traits>

#include "core/time.hpp"

namespace mallet {

//! What the input side tells the audio side at each cursor sample in the texture scene:
//! from t_ns on, the displayed cursor moves at this speed, over the disc or not.
struct StripeMotion {
  Nanos t_ns = 0;
  double speed_m_per_s = 0;
  bool on_texture = false;
};
static_assert(std::is_trivially_copyable_v<StripeMotion>);

struct StripeParams {
  double amplitude = 0.5;              //!< A, ratio of the actuator's full scale (before the gain knob)
  double wavelength_m = 0.002;         //!< λ: stripe spacing in world metres
  double phase_rad = 0.0;              //!< φ
  double fade_s = 0.005;               //!< envelope ramp at start/stop and at the disc's edge
  double rest_speed_m_per_s = 0.001;   //!< slower than this is "at rest"
  double max_freq_hz = 1000.0;         //!< v/λ is capped here
  //! A pointer that stops sends no more samples: this long after the last motion update
  //! the cursor counts as at rest (speed 0 from then on).
  double motion_timeout_s = 0.05;
};

//! The phase of Eq. 1 as a function of time since the last motion update (pure, exact).
class StripePhase {
 public:
  explicit StripePhase(const StripeParams& p) : p_(p) {}

  //! A new motion update after `dt_s` seconds of the previous one's speed.
  void update(double dt_s, double speed_m_per_s);
  //! Distance travelled since the gesture started, `dt_s` after the last update.
  double distance_at(double dt_s) const;
  //! 2π·distance/λ + φ reduced to [0, 2π).
  double phase_at(double dt_s) const;
  double speed() const { return speed_; }  //!< as used for the phase (capped)
  bool moving() const { return speed_ > p_.rest_speed_m_per_s; }
  //! Ends the gesture: the next motion starts again from distance 0.
  void end_gesture();

 private:
  StripeParams p_;
  double base_ = 0, comp_ = 0;  //!< distance at the last update (Neumaier sum)
  double speed_ = 0;
};

//! The per-sample renderer used by the audio engine (and nothing else): the phase above
//! with the envelope, adding A·gain·env·sin(phase) into a buffer.
class StripeSignal {
 public:
  StripeSignal(const StripeParams& p, int sample_rate_hz);

  //! From the next rendered sample on: the cursor moves at `speed` and is (or is not)
  //! over the disc.
  void motion(double speed_m_per_s, bool on_texture);
  //! Adds `frames` samples of y(t)·gain to out.
  void add_to(double* out, int frames, double gain);

  double envelope() const { return env_; }
  //! The phase of Eq. 1 at the next sample to be rendered, in [0, 2π).
  double current_phase() const { return phase_.phase_at(static_cast<double>(since_update_) / fs_); }
  const StripePhase& phase() const { return phase_; }

 private:
  StripeParams p_;
  double fs_;
  double env_step_;
  std::int64_t timeout_samples_;
  StripePhase phase_;
  std::int64_t since_update_ = 0;  //!< samples since the last motion update
  bool on_texture_ = false;
  double env_ = 0;
};

}  // namespace mallet
