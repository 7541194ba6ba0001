#include "core/actuator_signal.hpp"

#include <cmath>
#include <sstream>

namespace mallet {

std::optional<std::int64_t> ActuatorSignal::end_sample(int sample_rate_hz) const {
  if (amplitude <= kSilenceAmplitude) return start.index;
  if (params.decay_per_s <= 0) return std::nullopt;
  const double t = std::log(amplitude / kSilenceAmplitude) / params.decay_per_s;
  return start.index + static_cast<std::int64_t>(std::ceil(t * sample_rate_hz)) + 1;
}

std::optional<std::string> actuator_band_problem(const Material& m, int sample_rate_hz) {
  const double nyquist = 0.5 * sample_rate_hz;
  if (m.actuator.freq_hz < nyquist) return std::nullopt;
  std::ostringstream out;
  out << "material " << m.name << ": actuator freq_hz " << m.actuator.freq_hz
      << " is at or above the Nyquist frequency " << nyquist << " Hz of a " << sample_rate_hz
      << " Hz sample rate; raise the sample rate or lower freq_hz";
  return out.str();
}

}  // namespace mallet
