#include "audio/actuator_inverse.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "audio/fft.hpp"

namespace mallet::audio {

double target_shape(double f, double low_hz, double high_hz) {
  const double hi = (f / high_hz) * (f / high_hz);
  if (!(low_hz > 0)) return 1 / std::sqrt(1 + hi * hi);
  const double lo = (f / low_hz) * (f / low_hz);
  return lo / std::sqrt(1 + lo * lo) / std::sqrt(1 + hi * hi);
}

InverseFilter design_inverse(std::span<const double> h, const ActuatorResponse& r, const InverseSpec& spec) {
  if (!(spec.gain_limit_db > 0 && spec.gain_limit_db <= 40))
    throw std::invalid_argument("the inverse's gain limit must be above 0 and at most 40 dB");
  if (!(spec.taps >= 16 && spec.taps <= 8192)) throw std::invalid_argument("the inverse has 16 to 8192 taps");
  std::vector<double> band_db;
  for (const ResponsePoint& p : r.points)
    if (p.freq_hz >= r.band_low_hz && p.freq_hz <= r.band_high_hz) band_db.push_back(p.magnitude_db);
  if (band_db.size() < 3 || !(r.sample_rate_hz > 0) || !(r.measured_low_hz > 0 && r.measured_low_hz < r.measured_high_hz))
    throw std::invalid_argument("the response has no usable band");
  const double weakest_db = *std::min_element(band_db.begin(), band_db.end());
  std::nth_element(band_db.begin(), band_db.begin() + static_cast<std::ptrdiff_t>(band_db.size() / 2), band_db.end());
  InverseFilter out;
  out.target_db = std::min(band_db[band_db.size() / 2], weakest_db + spec.gain_limit_db - 3.0);
  const double target = std::pow(10.0, out.target_db / 20.0);
  const double limit = std::pow(10.0, spec.gain_limit_db / 20.0);
  const double beta = (target / (2 * limit)) * (target / (2 * limit));

  const std::size_t n = fft_size_for(std::max<std::size_t>(4 * h.size(), 32 * static_cast<std::size_t>(spec.taps)));
  const Spectrum spectrum = real_dft(h, n);
  const double bin_hz = static_cast<double>(r.sample_rate_hz) / static_cast<double>(n);
  const auto bin_of = [&](double f) { return static_cast<std::size_t>(std::llround(f / bin_hz)); };
  // The chain's magnitude as measured wherever the sweep measured it (the response's measured
  // range), not only over the usable band: outside the band the inverse still divides by the
  // chain's true magnitude, so the equalised chain's phase inside the band is the target's own
  // (a minimum-phase phase depends on the magnitude everywhere).
  const std::size_t k_lo = std::max<std::size_t>(1, bin_of(r.measured_low_hz));
  const std::size_t k_hi = std::min(spectrum.size() - 1, bin_of(r.measured_high_hz));
  const std::vector<double> chain = extended_magnitude(spectrum, k_lo, k_hi);
  // The target high-passes only a chain that falls below its band within the sweep (an
  // inertial actuator): one that reaches the sweep's bottom is kept flat down to DC.
  const double high_pass_hz = r.band_low_hz > r.measured_low_hz * 1.01 ? r.band_low_hz : 0.0;
  std::vector<double> magnitude(spectrum.size());
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    const double f = static_cast<double>(k) * bin_hz;
    const double a = chain[k];
    magnitude[k] = std::clamp(target_shape(f, high_pass_hz, r.band_high_hz) * target * a / (a * a + beta), 1e-6, limit);
  }
  const Spectrum c = minimum_phase(magnitude, n);
  std::vector<double> taps = inverse_real_dft(c, n);
  taps.resize(static_cast<std::size_t>(spec.taps));
  const std::size_t fade = taps.size() / 8;
  for (std::size_t i = 0; i < fade; ++i) {
    const double x = static_cast<double>(i + 1) / static_cast<double>(fade + 1);  // 0 → 1 toward the end
    taps[taps.size() - fade + i] *= 0.5 + 0.5 * std::cos(std::numbers::pi * x);
  }
  out.taps = std::move(taps);

  // What the cut filter does over the band: its gains and its latency.
  double weighted = 0, weights = 0;
  out.max_gain_db = -1e9;
  out.min_gain_db = 1e9;
  for (const ResponsePoint& p : r.points) {
    if (p.freq_hz < r.band_low_hz || p.freq_hz > r.band_high_hz) continue;
    const double gain_db = 20 * std::log10(std::abs(response_at(out.taps, p.freq_hz, r.sample_rate_hz)));
    out.max_gain_db = std::max(out.max_gain_db, gain_db);
    out.min_gain_db = std::min(out.min_gain_db, gain_db);
    const double w = std::pow(10.0, p.magnitude_db / 20.0);
    weighted += w * group_delay_at(out.taps, p.freq_hz, r.sample_rate_hz);
    weights += w;
  }
  out.latency_samples = weights > 0 ? weighted / weights : 0.0;
  return out;
}

}  // namespace mallet::audio
