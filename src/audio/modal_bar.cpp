#include "audio/modal_bar.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace mallet::audio {

namespace {

// A mode at or above this fraction of the sample rate is left out: its rotator would be
// exact, but the note's spectrum there is aliasing waiting for any later processing.
constexpr double kHighestModeFraction = 0.45;
// c_k's ceiling: a very fast strike may brighten a mode at most this much.
constexpr double kMaxBrightening = 4.0;

// s = v / v_ref, with a still, backward, NaN or meaningless strike made silent.
double relative_speed(const ModalPreset& preset, double speed_m_per_s) {
  if (!(speed_m_per_s > 0.0)) return 0.0;
  if (!(preset.reference_speed_m_per_s > 0.0)) return 1.0;
  return speed_m_per_s / preset.reference_speed_m_per_s;
}

// E(s): linear up to the reference speed, then a rational knee with the same slope that
// tends to full scale 1 (written as 1 − …/… so that s = +inf gives exactly 1, not NaN).
double compressed_amplitude(double loudness, double s) {
  if (s <= 1.0) return loudness * s;
  const double headroom = 1.0 - loudness;
  return 1.0 - headroom * headroom / (headroom - loudness + loudness * s);
}

// c_k(σ) = min(4, σ^(brightness·(ratio−1)/ratio)); 1 for the fundamental.
double brightening(const ModalPreset& preset, const Mode& mode, double sigma) {
  if (!(mode.ratio > 0.0)) return 0.0;
  const double exponent = std::max(0.0, preset.brightness) * (mode.ratio - 1.0) / mode.ratio;
  if (exponent == 0.0) return 1.0;
  const double c = std::pow(sigma, exponent);  // σ = 0 → 0 (or +inf for a mode below f0)
  return std::isnan(c) ? 0.0 : std::min(kMaxBrightening, c);
}

}  // namespace

double ModalBarVoice::note_amplitude(const ModalPreset& preset, double speed_m_per_s) {
  return compressed_amplitude(std::clamp(preset.loudness, 0.0, 1.0), relative_speed(preset, speed_m_per_s));
}

void ModalBarVoice::strike(const ModalPreset& preset, double fundamental_hz, double speed_m_per_s,
                           double delay_s, int sample_rate_hz) {
  count_ = 0;
  if (sample_rate_hz <= 0 || !(fundamental_hz > 0.0) || !std::isfinite(fundamental_hz)) return;
  const double loudness = std::clamp(preset.loudness, 0.0, 1.0);
  const double amplitude = compressed_amplitude(loudness, relative_speed(preset, speed_m_per_s));
  if (!(amplitude > 0.0)) return;  // at rest, or a silent preset
  const double sigma = amplitude / loudness;  // the effective speed: the timbre saturates with E

  const std::size_t n = std::min(preset.modes.size(), static_cast<std::size_t>(kMaxModes));
  std::array<double, kMaxModes> weight{};
  double total = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Mode& m = preset.modes[k];
    weight[k] = std::max(0.0, m.gain) * brightening(preset, m, sigma);
    total += weight[k];
  }
  if (!(total > 0.0) || !std::isfinite(total)) return;

  const double highest_hz = kHighestModeFraction * sample_rate_hz;
  for (std::size_t k = 0; k < n; ++k) {
    const Mode& m = preset.modes[k];
    const double freq_hz = m.ratio * fundamental_hz;
    if (!(freq_hz < highest_hz) || weight[k] == 0.0) continue;
    modes_[static_cast<std::size_t>(count_)].start(amplitude * weight[k] / total,
                                                   std::max(0.0, m.decay_per_s), freq_hz, delay_s,
                                                   sample_rate_hz);
    ++count_;
  }
}

double ModalBarVoice::tick() {
  double sum = 0.0;
  for (int k = 0; k < count_; ++k) sum += modes_[static_cast<std::size_t>(k)].tick();
  return sum;
}

double ModalBarVoice::envelope() const {
  double sum = 0.0;
  for (int k = 0; k < count_; ++k) sum += modes_[static_cast<std::size_t>(k)].envelope();
  return sum;
}

void ModalBarVoice::stop() {
  for (int k = 0; k < count_; ++k) modes_[static_cast<std::size_t>(k)].stop();
  count_ = 0;
}

}  // namespace mallet::audio
