#include "audio/actuator_response.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "audio/fft.hpp"

namespace mallet::audio {

namespace {

constexpr double kPi = std::numbers::pi;

double db(double linear) { return 20.0 * std::log10(std::max(linear, 1e-300)); }

}  // namespace

std::vector<double> extended_magnitude(std::span<const std::complex<double>> spectrum, std::size_t k_lo, std::size_t k_hi) {
  k_lo = std::clamp<std::size_t>(k_lo, 1, spectrum.size() - 1);
  k_hi = std::clamp(k_hi, k_lo, spectrum.size() - 1);
  // The log-log slope over the octave inside the low edge and the half octave inside the
  // high one (nearer a roll-off's asymptote), continued outward.
  const auto log_mag = [&](std::size_t k) { return std::log(std::max(std::abs(spectrum[k]), 1e-300)); };
  const std::size_t lo_ref = std::min(2 * k_lo, k_hi), hi_ref = std::max(static_cast<std::size_t>(static_cast<double>(k_hi) / std::numbers::sqrt2), k_lo);
  double lo_slope = lo_ref > k_lo ? (log_mag(lo_ref) - log_mag(k_lo)) / std::log(static_cast<double>(lo_ref) / static_cast<double>(k_lo)) : 0.0;
  // A chain that is nearly flat at the sweep's bottom (less than 6 dB an octave: below a
  // resonance, not an inertial actuator's 12) is held flat down to DC: continuing the slow
  // rise toward its resonance would make it weaker at DC than it is.
  if (lo_slope < 1.0) lo_slope = 0.0;
  const double hi_slope = k_hi > hi_ref ? (log_mag(k_hi) - log_mag(hi_ref)) / std::log(static_cast<double>(k_hi) / static_cast<double>(hi_ref)) : 0.0;
  std::vector<double> magnitude(spectrum.size());
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    double v;
    if (k < k_lo)
      v = log_mag(k_lo) + lo_slope * std::log(static_cast<double>(std::max<std::size_t>(k, 1)) / static_cast<double>(k_lo));
    else if (k > k_hi)
      v = log_mag(k_hi) + hi_slope * std::log(static_cast<double>(k) / static_cast<double>(k_hi));
    else
      v = log_mag(k);
    magnitude[k] = std::exp(std::clamp(v, log_mag(k < k_lo ? k_lo : k_hi) - 80 * std::log(10.0) / 20, 700.0));
  }
  return magnitude;
}

double flat_path_delay(std::span<const double> h, std::size_t pre) {
  std::size_t k = 0;
  for (std::size_t i = 1; i < h.size(); ++i)
    if (std::abs(h[i]) > std::abs(h[k])) k = i;
  double offset = 0;
  if (k > 0 && k + 1 < h.size()) {
    const double a = std::abs(h[k - 1]), b = std::abs(h[k]), c = std::abs(h[k + 1]);
    const double d = a - 2 * b + c;
    if (d != 0) offset = 0.5 * (a - c) / d;
  }
  return static_cast<double>(k) + offset - static_cast<double>(pre);
}

std::complex<double> response_at(std::span<const double> h, double freq_hz, int rate) {
  const double w = 2 * kPi * freq_hz / rate;
  const std::complex<double> step = std::polar(1.0, -w);
  std::complex<double> z = 1.0, sum = 0.0;
  for (std::size_t n = 0; n < h.size(); ++n) {
    sum += h[n] * z;
    z *= step;
    if ((n & 1023) == 1023) z = std::polar(1.0, -w * static_cast<double>(n + 1));  // no drift
  }
  return sum;
}

double group_delay_at(std::span<const double> h, double freq_hz, int rate) {
  const double w = 2 * kPi * freq_hz / rate;
  std::complex<double> sum = 0.0, ramp = 0.0;
  for (std::size_t n = 0; n < h.size(); ++n) {
    const std::complex<double> z = std::polar(1.0, -w * static_cast<double>(n));
    sum += h[n] * z;
    ramp += static_cast<double>(n) * h[n] * z;
  }
  return std::norm(sum) > 0 ? (ramp / sum).real() : 0.0;
}

std::vector<std::complex<double>> minimum_phase(std::span<const double> magnitude, std::size_t n) {
  if (magnitude.size() != n / 2 + 1) throw std::invalid_argument("minimum_phase: n/2 + 1 bins expected");
  Spectrum log_mag(magnitude.size());
  for (std::size_t k = 0; k < magnitude.size(); ++k) log_mag[k] = std::log(std::max(magnitude[k], 1e-300));
  std::vector<double> cepstrum = inverse_real_dft(log_mag, n);
  // Fold: the anticausal half onto the causal one.
  for (std::size_t i = 1; i < n / 2; ++i) cepstrum[i] *= 2.0;
  for (std::size_t i = n / 2 + 1; i < n; ++i) cepstrum[i] = 0.0;
  Spectrum folded = real_dft(cepstrum, n);
  for (auto& v : folded) v = std::exp(v);
  return folded;
}

ActuatorResponse analyse_response(std::span<const double> h, int rate, double f1_hz, double f2_hz, double band_db,
                                  std::size_t pre) {
  if (h.empty() || !(f1_hz > 0 && f1_hz < f2_hz && f2_hz < rate / 2.0))
    throw std::invalid_argument("analyse_response: an impulse response and 0 < f1 < f2 < rate/2 are needed");
  ActuatorResponse r;
  r.sample_rate_hz = rate;
  const double step = std::pow(2.0, 1.0 / 12.0);
  double previous_phase = 0;
  bool first = true;
  for (double f = f1_hz; f <= f2_hz * 1.0000001; f *= step) {
    // Time from h[pre]: the pre samples' linear phase taken back out.
    const std::complex<double> v = response_at(h, f, rate) * std::polar(1.0, 2 * kPi * f / rate * static_cast<double>(pre));
    double phase = std::arg(v) * 180.0 / kPi;
    const double delay_samples = group_delay_at(h, f, rate) - static_cast<double>(pre);
    if (!first) {
      // Unwrapped toward where the group delay says the phase went: a long delay turns the
      // phase by more than half a turn between two points.
      const ResponsePoint& last = r.points.back();
      const double mean_delay_s = 0.5 * (last.group_delay_ms / 1000.0 + delay_samples / rate);
      const double predicted = previous_phase - 360.0 * (f - last.freq_hz) * mean_delay_s;
      phase += 360.0 * std::round((predicted - phase) / 360.0);
    }
    first = false;
    previous_phase = phase;
    r.points.push_back({f, db(std::abs(v)), phase, 1000.0 * delay_samples / rate});
  }
  // The resonance and the usable band, a third of an octave inside the sweep.
  const double lo = f1_hz * std::pow(2.0, 1.0 / 3.0), hi = f2_hz / std::pow(2.0, 1.0 / 3.0);
  r.measured_low_hz = lo;
  r.measured_high_hz = f2_hz / std::pow(2.0, 1.0 / 6.0);
  std::size_t peak = r.points.size();
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    if (r.points[i].freq_hz < lo || r.points[i].freq_hz > hi) continue;
    if (peak == r.points.size() || r.points[i].magnitude_db > r.points[peak].magnitude_db) peak = i;
  }
  if (peak == r.points.size()) throw std::invalid_argument("analyse_response: the sweep's range is too narrow");
  r.resonance_hz = r.points[peak].freq_hz;
  r.resonance_db = r.points[peak].magnitude_db;
  const auto usable = [&](std::size_t i) {
    return r.points[i].freq_hz >= lo && r.points[i].freq_hz <= hi &&
           r.points[i].magnitude_db >= r.resonance_db - band_db;
  };
  std::size_t a = peak, b = peak;
  while (a > 0 && usable(a - 1)) --a;
  while (b + 1 < r.points.size() && usable(b + 1)) ++b;
  r.band_low_hz = r.points[a].freq_hz;
  r.band_high_hz = r.points[b].freq_hz;

  // The pure delay: the excess phase over the band.
  const std::size_t n = fft_size_for(std::max<std::size_t>(4 * h.size(), 16384));
  const Spectrum spectrum = real_dft(h, n);
  const double bin_hz = static_cast<double>(rate) / static_cast<double>(n);
  const auto bin_of = [&](double f) { return static_cast<std::size_t>(std::llround(f / bin_hz)); };
  const std::size_t k_lo = std::max<std::size_t>(1, bin_of(r.band_low_hz));
  const std::size_t k_hi = std::min(spectrum.size() - 1, bin_of(r.band_high_hz));
  const Spectrum m = minimum_phase(extended_magnitude(spectrum, bin_of(r.measured_low_hz), bin_of(r.measured_high_hz)), n);
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, unwrapped = 0, previous = 0;
  for (std::size_t k = k_lo; k <= k_hi; ++k) {
    double phase = std::arg(spectrum[k] / m[k]);
    if (k == k_lo) {
      unwrapped = phase;
    } else {
      double d = phase - previous;
      while (d > kPi) d -= 2 * kPi;
      while (d < -kPi) d += 2 * kPi;
      unwrapped += d;
    }
    previous = phase;
    const double w = 2 * kPi * static_cast<double>(k) / static_cast<double>(n);
    const double weight = std::abs(spectrum[k]);
    sw += weight;
    sx += weight * w;
    sy += weight * unwrapped;
    sxx += weight * w * w;
    sxy += weight * w * unwrapped;
  }
  const double denominator = sw * sxx - sx * sx;
  if (denominator > 0) {
    const double slope = (sw * sxy - sx * sy) / denominator;
    const double intercept = (sy - slope * sx) / sw;
    r.delay_samples = -slope - static_cast<double>(pre);
    const double wrapped = std::remainder(intercept, 2 * kPi);
    r.inverted = std::abs(wrapped) > kPi / 2;
  }
  return r;
}

}  // namespace mallet::audio
