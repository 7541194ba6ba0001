#pragma once
// Eq. 1 of both papers (Okamura's decaying sinusoid):
//     Q(t) = A(v) · e^(−B·t) · sin(2π·f·t),   A(v) = A·v
// t is the time since the impact and v the normal impact speed in m/s. The same law
// drives the visual vibration (A in seconds, so A·v is metres of cursor displacement)
// and the actuator (A a ratio of full scale). Table 1 of "Virtual Chromatic
// Percussions" gives the parameters; they live in config/materials.toml.
#include <string>

#include "core/time.hpp"

namespace mallet {

//! The material triple of Eq. 1. Units depend on the use: see VisualVibration and
//! ActuatorSignal.
struct VibrationParams {
  double amplitude = 0.0;    //!< A: seconds (visual) or ratio of full scale (actuator)
  double decay_per_s = 0.0;  //!< B ≥ 0; 0 = undamped
  double freq_hz = 0.0;      //!< f > 0

  friend bool operator==(const VibrationParams&, const VibrationParams&) = default;
};

//! Beyond this exponent e^(−B·t) is below 1e-260: return an exact zero. The margin
//! keeps e^(−B·t)·sin(...) out of the subnormal range (below 2.2e-308) even next to a
//! zero crossing, where subnormal arithmetic is slow on x86 and useless to the output.
inline constexpr double kDecayCutoffExponent = 600.0;

//! e^(−B·t) · sin(2π·f·t) for t seconds since the impact; 0 for t < 0.
//! The phase is reduced with the whole and fractional seconds kept apart so an
//! undamped signal stays exact after days.
double decaying_sine_unit(const VibrationParams& p, Nanos since_impact);

//! Same law for a time given in (fractional) seconds; used by the sample renderer where
//! a sample instant falls between two nanoseconds.
double decaying_sine_unit_seconds(const VibrationParams& p, double since_impact_s);

//! Q(t) of Eq. 1 with A(v) = A·v.
inline double eq1(const VibrationParams& p, double impact_speed, Nanos since_impact) {
  return p.amplitude * impact_speed * decaying_sine_unit(p, since_impact);
}

//! Time after which |Q| stays below `fraction` of A(v): ln(1/fraction)/B; a very long
//! time when B = 0.
double decay_time_s(const VibrationParams& p, double fraction);

}  // namespace mallet
