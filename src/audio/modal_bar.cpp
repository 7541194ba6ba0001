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
    if (count_ >= preset.max_sounding_modes) break;
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

namespace {

// The modes of one voice advance side by side: `Lanes` independent rotators per sample
// instead of one long dependency chain each, so the CPU overlaps them (and the compiler
// can vectorise the rotation). Unused lanes are zero and add exactly 0.0; the modes are
// summed in the same order as tick(), so the output is the same to the last bit.
template <int Lanes>
void add_modes(std::array<DampedOscillator, ModalBarVoice::kMaxModes>& modes, int count, double* out, int n) {
  int i = 0;
  while (i < n) {
    const int m = std::min(n - i, modes[0].until_reseed());  // all modes started together
    std::array<double, Lanes> re{}, im{}, c{}, s{};
    for (int j = 0; j < count; ++j) {
      const DampedOscillator::Lane l = modes[static_cast<std::size_t>(j)].lane();
      re[j] = l.re;
      im[j] = l.im;
      c[j] = l.c;
      s[j] = l.s;
    }
    for (int k = 0; k < m; ++k) {
      double sum = 0.0;
      for (int j = 0; j < Lanes; ++j) sum += im[j];
      for (int j = 0; j < Lanes; ++j) {
        const double r = re[j] * c[j] - im[j] * s[j];
        im[j] = re[j] * s[j] + im[j] * c[j];
        re[j] = r;
      }
      out[i + k] += sum;
    }
    for (int j = 0; j < count; ++j)
      modes[static_cast<std::size_t>(j)].finish_run({re[j], im[j], c[j], s[j]}, m);
    i += m;
  }
}

}  // namespace

void ModalBarVoice::add_to(double* out, int n) {
  if (count_ == 0) return;
  if (count_ <= 4) add_modes<4>(modes_, count_, out, n);
  else add_modes<kMaxModes>(modes_, count_, out, n);
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
