#include "audio/exp_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "audio/fft.hpp"

namespace mallet::audio {

namespace {

void check(const SweepSpec& s) {
  const double nyquist = s.sample_rate_hz / 2.0;
  if (!(s.sample_rate_hz > 0 && s.f1_hz > 0 && s.f1_hz < s.f2_hz && s.f2_hz < nyquist))
    throw std::invalid_argument("the sweep needs 0 < f1 < f2 < half the sample rate");
  if (!(s.duration_s >= 0.1 && s.duration_s <= 60))
    throw std::invalid_argument("the sweep lasts 0.1 to 60 s");
  if (!(s.level_db <= 0 && s.level_db >= -100)) throw std::invalid_argument("the sweep's level is -100 to 0 dB");
  if (!(s.fade_s >= 0 && 2 * s.fade_s < s.duration_s)) throw std::invalid_argument("the fades are longer than the sweep");
}

}  // namespace

std::vector<double> exp_sweep(const SweepSpec& s) {
  check(s);
  const double rate = s.sample_rate_hz;
  const auto n = static_cast<std::size_t>(std::llround(s.duration_s * rate));
  const double big_l = s.duration_s / std::log(s.f2_hz / s.f1_hz);
  const double a = std::pow(10.0, s.level_db / 20.0);
  const auto fade = static_cast<std::size_t>(std::llround(s.fade_s * rate));
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / rate;
    double g = a;
    const std::size_t from_end = n - 1 - i;
    if (i < fade) g *= 0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(i) / static_cast<double>(fade));
    if (from_end < fade)
      g *= 0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(from_end) / static_cast<double>(fade));
    x[i] = g * std::sin(2 * std::numbers::pi * s.f1_hz * big_l * std::expm1(t / big_l));
  }
  return x;
}

std::vector<double> deconvolve_sweep(std::span<const double> recorded, std::span<const double> sweep,
                                     const SweepSpec& spec, std::size_t length, std::size_t pre) {
  check(spec);
  if (recorded.size() < sweep.size()) throw std::invalid_argument("the recording is shorter than the sweep");
  const std::size_t n = fft_size_for(recorded.size() + sweep.size());
  const Spectrum x = real_dft(sweep, n);
  Spectrum y = real_dft(recorded, n);
  double peak = 0;
  for (const auto& v : x) peak = std::max(peak, std::norm(v));
  const double bin_hz = static_cast<double>(spec.sample_rate_hz) / static_cast<double>(n);
  // Outside the sweep the division is faded out over an octave (a raised cosine in log
  // frequency) rather than cut: a brick wall at f1 rings for about 1/f1 on both sides of
  // the response, and the part before its first sample would be lost.
  const auto fade = [](double octaves_out) {
    if (octaves_out <= 0) return 1.0;
    if (octaves_out >= 1) return 0.0;
    return 0.5 + 0.5 * std::cos(std::numbers::pi * octaves_out);
  };
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double f = std::max(static_cast<double>(k) * bin_hz, 1e-9);
    const double w = fade(std::log2(spec.f1_hz / f)) * fade(std::log2(f / spec.f2_hz));
    y[k] = w * y[k] * std::conj(x[k]) / (std::norm(x[k]) + 1e-6 * peak);
  }
  const std::vector<double> circular = inverse_real_dft(y, n);
  // From `pre` samples before the sweep's first sample (the end of the circular result).
  std::vector<double> h(length, 0.0);
  for (std::size_t i = 0; i < length && i < n; ++i) h[i] = circular[(i + n - pre % n) % n];
  return h;
}

}  // namespace mallet::audio
