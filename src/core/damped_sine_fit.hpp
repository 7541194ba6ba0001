#pragma once
// Recovers Eq. 1's parameters from a rendered signal, so that a stimulus can be checked
// against the material table instead of trusted: y(t) = a·e^(−b·t)·sin(2π·f·t + φ).
// Start values come from zero crossings (f) and a log-linear fit of the half-cycle
// peaks (b, a); Levenberg–Marquardt then minimises the squared residual.
#include <span>

namespace mallet {

struct DampedSineFit {
  double amplitude = 0;    //!< a
  double decay_per_s = 0;  //!< b
  double freq_hz = 0;      //!< f
  double phase_rad = 0;    //!< φ
  double rms_residual = 0; //!< relative to a
  bool ok = false;         //!< false when the signal has too few cycles to fit
};

//! `y[i]` is the signal at t = t0_s + i / rate_hz, t measured from the impact.
DampedSineFit fit_damped_sine(std::span<const double> y, double rate_hz, double t0_s = 0.0);

}  // namespace mallet
