#pragma once
// The actuator's safe full-scale limit. Identity up to the knee, so every stimulus
// below it is exactly Eq. 1; above it a tanh shoulder with slope 1 at the knee that
// approaches ±1 and never exceeds it (a voice coil driven past full scale buzzes and
// heats).
#include <cmath>

namespace mallet {

inline double soft_clip(double x, double knee = 0.9) {
  const double a = std::fabs(x);
  if (a <= knee) return x;
  const double room = 1.0 - knee;
  const double y = knee + room * std::tanh((a - knee) / room);
  return x < 0 ? -y : y;
}

}  // namespace mallet
