#pragma once
// What the stick carries, checked against Table 1: the strikes `mallet calibrate actuator
// --verify` plays (wood and metal at three speeds, each alone), rendered as the engine
// renders the actuator channel (Eq. 1 at [actuator] gain, on its own sample, then the
// inverse when one is in force), and B and f fitted back out of the sensor's recording of
// them with the project's damped-sine fit (core/damped_sine_fit.hpp).
//
// The fit of strike k starts at its first sample plus the chain's delay (rounded) and
// lasts until Eq. 1's envelope is 60 dB down (ln(1000)/B), at most 0.4 s.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/damped_sine_fit.hpp"
#include "core/material.hpp"

namespace mallet::audio {

struct FeltStrike {
  std::string material;
  double speed_m_per_s = 0;
  VibrationParams table;      //!< the material's actuator triple (Table 1)
  std::int64_t start = 0;     //!< its first sample in the played signal
};

struct FeltFit {
  DampedSineFit fit;
  double decay_error = 0;  //!< (fitted B − Table 1's B) / Table 1's B
  double freq_error = 0;   //!< likewise for f
};

inline constexpr double kFeltSpeeds[3] = {0.3, 0.6, 1.0};  //!< m/s

//! `materials` at each of kFeltSpeeds, one every `spacing_s`, the first at `lead_s`.
std::vector<FeltStrike> felt_strikes(const std::vector<Material>& materials, int rate, double lead_s = 0.25,
                                     double spacing_s = 0.6);

//! The actuator channel for `strikes` (total samples), through `taps` when not empty.
std::vector<float> render_felt(const std::vector<FeltStrike>& strikes, double gain, std::span<const double> taps,
                               std::size_t total, int rate);

//! B and f of each strike in `recording`, the chain's delay being `delay_samples`.
std::vector<FeltFit> fit_felt(const std::vector<FeltStrike>& strikes, std::span<const double> recording,
                              double delay_samples, int rate);

}  // namespace mallet::audio
