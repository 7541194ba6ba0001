#pragma once
// The vibrotactile signal of "Virtual Chromatic Percussions" §3.2.2: Eq. 1 with the
// material's *actuator* triple, the amplitude scaled by the impact speed and by the
// operator's gain (the paper's rotary switch on the amplifier), then soft-clipped at
// full scale (see soft_clip.hpp).
#include <optional>
#include <string>

#include "core/impact.hpp"
#include "core/material.hpp"
#include "core/sample_clock.hpp"
#include "core/vibration.hpp"

namespace mallet {

//! Below this envelope (−100 dB of full scale) a voice is finished.
inline constexpr double kSilenceAmplitude = 1e-5;

struct ActuatorSignal {
  SampleAlignment start;  //!< the impact's own sample
  double amplitude = 0;   //!< gain · A · v, in full-scale units, before clipping
  VibrationParams params;

  ActuatorSignal(const Impact& impact, const VibrationParams& actuator, double gain,
                 int sample_rate_hz)
      : start(align_to_sample(impact.t_ns, sample_rate_hz)),
        amplitude(gain * actuator.amplitude * impact.speed_m_per_s),
        params(actuator) {}

  //! Eq. 1 at sample n (0 before the impact's sample).
  double at_sample(std::int64_t n, int sample_rate_hz) const {
    if (n < start.index) return 0.0;
    return amplitude * decaying_sine_unit_seconds(params, seconds_since(start, n, sample_rate_hz));
  }

  //! The first sample from which the envelope stays below kSilenceAmplitude, or
  //! nothing for an undamped signal.
  std::optional<std::int64_t> end_sample(int sample_rate_hz) const;
};

//! Why a material's actuator signal cannot be played at this rate, or nothing.
//! f at or above Nyquist is refused, not aliased: the actuator would get a different
//! frequency than the one configured.
std::optional<std::string> actuator_band_problem(const Material& m, int sample_rate_hz);

}  // namespace mallet
