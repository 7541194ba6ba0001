#pragma once
// The acoustic note of a struck bar by modal synthesis: a few exponentially decaying
// partials (one DampedOscillator each) at the bar's mode ratios. Presets are data
// (config/instruments.toml): xylophone (tuned wooden bar, first overtone at 3×),
// glockenspiel (uniform metal bar, 1 : 2.756 : 5.404 : 8.933), marimba, vibraphone.
// The strike speed sets loudness and brightness: the law is written at ModalPreset
// (src/core/modal_preset.hpp); in short, the note's amplitude is linear in v up to the
// reference speed, then soft-compressed below full scale, and mode k's share grows as
// (v/v_ref)^(brightness·(ratio_k−1)/ratio_k) (at most 4×, and no faster than the
// compressed loudness above the reference speed).
//
// Real-time safe: strike() and tick() never allocate, lock or throw.
#include <array>

#include "audio/damped_oscillator.hpp"
#include "core/modal_preset.hpp"

namespace mallet::audio {

using Mode = mallet::Mode;
using ModalPreset = mallet::ModalPreset;

class ModalBarVoice {
 public:
  static constexpr int kMaxModes = kMaxModalModes;

  //! Starts the note; the next tick() is `delay_s` after the strike. Every mode starts at
  //! sin(0), so the note is exactly 0 at the strike instant. Modes at or above
  //! 0.45·sample_rate are left out (they could only alias); so are modes beyond kMaxModes.
  void strike(const ModalPreset& preset, double fundamental_hz, double speed_m_per_s, double delay_s,
              int sample_rate_hz);
  double tick();
  //! Adds the next `n` samples to `out` (same values as n calls of tick()).
  void add_to(double* out, int n);
  double envelope() const;  //!< sum of the modes' envelopes: an upper bound of |output|
  void stop();
  int active_modes() const { return count_; }  //!< modes sounding since the last strike()

  //! E(v) of the strike law: the sum of the modes' initial amplitudes, in [0, 1].
  static double note_amplitude(const ModalPreset& preset, double speed_m_per_s);

 private:
  std::array<DampedOscillator, kMaxModes> modes_{};
  int count_ = 0;
};

}  // namespace mallet::audio
