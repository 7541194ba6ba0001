#include "audio/felt_signal.hpp"

#include <algorithm>
#include <cmath>

#include "audio/fir_filter.hpp"
#include "core/vibration.hpp"

namespace mallet::audio {

std::vector<FeltStrike> felt_strikes(const std::vector<Material>& materials, int rate, double lead_s, double spacing_s) {
  std::vector<FeltStrike> out;
  double t = lead_s;
  for (const Material& m : materials)
    for (double v : kFeltSpeeds) {
      out.push_back({m.name, v, m.actuator, static_cast<std::int64_t>(std::llround(t * rate))});
      t += spacing_s;
    }
  return out;
}

std::vector<float> render_felt(const std::vector<FeltStrike>& strikes, double gain, std::span<const double> taps,
                               std::size_t total, int rate) {
  std::vector<double> mix(total, 0.0);
  for (const FeltStrike& s : strikes) {
    const double a = gain * s.table.amplitude * s.speed_m_per_s;
    for (std::int64_t n = s.start; n < static_cast<std::int64_t>(total); ++n) {
      const double since = static_cast<double>(n - s.start) / rate;
      if (s.table.decay_per_s > 0 && s.table.decay_per_s * since > kDecayCutoffExponent) break;
      mix[static_cast<std::size_t>(n)] += a * decaying_sine_unit_seconds(s.table, since);
    }
  }
  FirFilter inverse(std::vector<double>(taps.begin(), taps.end()));
  std::vector<float> out(total);
  for (std::size_t n = 0; n < total; ++n) out[n] = static_cast<float>(inverse.tick(mix[n]));
  return out;
}

std::vector<FeltFit> fit_felt(const std::vector<FeltStrike>& strikes, std::span<const double> recording,
                              double delay_samples, int rate) {
  std::vector<FeltFit> out;
  const auto delay = static_cast<std::int64_t>(std::llround(delay_samples));
  for (const FeltStrike& s : strikes) {
    const double length_s = s.table.decay_per_s > 0 ? std::min(0.4, std::log(1000.0) / s.table.decay_per_s) : 0.4;
    // From the strike's largest sample within two of its periods after it arrives: a chain
    // delays a strike's onset by its group delay too, and a damped sine fitted from before
    // its onset reads the silence as a wrong B. (Eq. 1 is largest in its first period.)
    const std::int64_t arrival = s.start + delay;
    const std::int64_t search = std::max<std::int64_t>(2, static_cast<std::int64_t>(2.0 * rate / s.table.freq_hz));
    std::int64_t from = arrival;
    for (std::int64_t n = std::max<std::int64_t>(arrival, 0); n < arrival + search && n < static_cast<std::int64_t>(recording.size()); ++n)
      if (std::abs(recording[static_cast<std::size_t>(n)]) > std::abs(recording[static_cast<std::size_t>(from)])) from = n;
    const std::int64_t to = std::min<std::int64_t>(from + static_cast<std::int64_t>(length_s * rate),
                                                   static_cast<std::int64_t>(recording.size()));
    FeltFit f;
    if (from >= 0 && to > from) {
      f.fit = fit_damped_sine(recording.subspan(static_cast<std::size_t>(from), static_cast<std::size_t>(to - from)), rate);
      if (f.fit.ok) {
        f.decay_error = (f.fit.decay_per_s - s.table.decay_per_s) / s.table.decay_per_s;
        f.freq_error = (f.fit.freq_hz - s.table.freq_hz) / s.table.freq_hz;
      }
    }
    out.push_back(f);
  }
  return out;
}

}  // namespace mallet::audio
