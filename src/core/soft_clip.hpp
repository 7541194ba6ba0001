#pragma once
// A safe full-scale limit for one sample. Identity up to the knee, so every stimulus
// below it is exactly Eq. 1; above it a tanh shoulder with slope 1 at the knee that
// approaches ±ceiling and never exceeds it (a voice coil driven past full scale buzzes and
// heats). The audio engine applies it through audio/peak_limiter.hpp, to a held envelope
// rather than to each sample, with a ceiling below full scale.
#include <cmath>

namespace mallet {

inline double soft_clip(double x, double knee = 0.9, double ceiling = 1.0) {
  const double a = std::fabs(x);
  if (a <= knee) return x;
  const double room = ceiling - knee;
  const double y = knee + room * std::tanh((a - knee) / room);
  return x < 0 ? -y : y;
}

}  // namespace mallet
