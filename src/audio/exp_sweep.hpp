#pragma once
// Farina's exponential sine sweep, and the impulse response a recording of it gives.
//
//   x(t) = a · sin(2π · f1 · L · (e^(t/L) − 1)),   L = T / ln(f2 / f1),  0 ≤ t < T
//
// The instantaneous frequency f1·e^(t/L) rises from f1 to f2 in T seconds, spending equal
// time in each octave; the first and last fade_s are faded in and out (half Hann) so the
// actuator is not kicked. A recording y of the sweep through a chain gives the chain's
// impulse response by regularised spectral division (Kirkeby's form):
//
//   H(k) = W(k) · Y(k) · X*(k) / (|X(k)|² + ε),   ε = 1e-6 · max|X|²,
//
// W fading the result out over the octave below f1 and the octave above f2 (a raised
// cosine in log frequency: the sweep put nothing there, and a brick wall would ring),
// on one FFT long enough that the linear convolution does not wrap. A weakly nonlinear
// chain's harmonics land at negative times (the end of the circular result): the
// response's first `length` samples are the linear part alone.
#include <cstddef>
#include <span>
#include <vector>

namespace mallet::audio {

struct SweepSpec {
  double f1_hz = 20.0;
  double f2_hz = 2000.0;
  double duration_s = 4.0;  //!< T
  double level_db = -20.0;  //!< the peak, dB of full scale
  double fade_s = 0.02;     //!< half-Hann fade in and out
  int sample_rate_hz = 48000;
};

//! The sweep's samples (round(T · rate) of them). Throws std::invalid_argument for a spec
//! that cannot be played (0 < f1 < f2 < rate/2, T ≥ 0.1 s, level ≤ 0 dB).
std::vector<double> exp_sweep(const SweepSpec& spec);

//! The chain's impulse response, `length` samples from `pre` samples before the sweep's
//! first sample, from `recorded` (the input, sample-aligned with the sweep's output, at
//! least as long as the sweep). In the recording's units per unit of the output. W is
//! zero-phase, so the response is smeared by about 1/f1 to both sides of its onset: `pre`
//! (kDeconvolutionPre) keeps the part before it, whatever the chain's own delay.
inline constexpr std::size_t kDeconvolutionPre = 8192;
std::vector<double> deconvolve_sweep(std::span<const double> recorded, std::span<const double> sweep,
                                     const SweepSpec& spec, std::size_t length, std::size_t pre = kDeconvolutionPre);

}  // namespace mallet::audio
