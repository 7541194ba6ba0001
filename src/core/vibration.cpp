#include "core/vibration.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace mallet {

namespace {

double sine_and_decay(double decay_per_s, double t_s, double cycles) {
  const double exponent = decay_per_s * t_s;
  if (exponent > kDecayCutoffExponent) return 0.0;
  const double frac = cycles - std::floor(cycles);  // in [0, 1): keeps sin's argument small
  return std::exp(-exponent) * std::sin(2.0 * std::numbers::pi * frac);
}

}  // namespace

double decaying_sine_unit(const VibrationParams& p, Nanos since_impact) {
  if (since_impact < 0) return 0.0;
  const Nanos whole_s = since_impact / kNanosPerSecond;
  const Nanos rest_ns = since_impact % kNanosPerSecond;
  // f·whole_s is reduced to its fractional part before the sub-second part is added,
  // so the phase keeps its precision whatever the time since the impact.
  const double whole_cycles = p.freq_hz * static_cast<double>(whole_s);
  const double cycles = (whole_cycles - std::floor(whole_cycles)) +
                        p.freq_hz * static_cast<double>(rest_ns) * 1e-9;
  return sine_and_decay(p.decay_per_s, to_seconds(since_impact), cycles);
}

double decaying_sine_unit_seconds(const VibrationParams& p, double since_impact_s) {
  if (!(since_impact_s >= 0.0)) return 0.0;
  const double whole_s = std::floor(since_impact_s);
  const double whole_cycles = p.freq_hz * whole_s;
  const double cycles =
      (whole_cycles - std::floor(whole_cycles)) + p.freq_hz * (since_impact_s - whole_s);
  return sine_and_decay(p.decay_per_s, since_impact_s, cycles);
}

double decay_time_s(const VibrationParams& p, double fraction) {
  if (p.decay_per_s <= 0.0 || fraction <= 0.0) return std::numeric_limits<double>::infinity();
  return std::log(1.0 / fraction) / p.decay_per_s;
}

}  // namespace mallet
