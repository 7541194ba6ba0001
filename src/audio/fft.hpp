#pragma once
// Real discrete Fourier transforms through FFTW3 (double precision), for the actuator's
// measurement and the design of its inverse. On the caller's thread only, never in an audio
// callback: FFTW's planner allocates and is not thread-safe (a process-wide mutex guards it).
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

namespace mallet::audio {

using Spectrum = std::vector<std::complex<double>>;

//! The n-point DFT of x, zero-padded (or cut) to n samples: n/2 + 1 bins,
//! X[k] = Σ x[i]·e^(−2πi·ik/n).
Spectrum real_dft(std::span<const double> x, std::size_t n);

//! The inverse of real_dft: n samples from n/2 + 1 bins, divided by n, so that
//! inverse_real_dft(real_dft(x, n), n) gives x back.
std::vector<double> inverse_real_dft(std::span<const std::complex<double>> spectrum, std::size_t n);

//! The smallest power of two ≥ n (at least 2).
std::size_t fft_size_for(std::size_t n);

}  // namespace mallet::audio
