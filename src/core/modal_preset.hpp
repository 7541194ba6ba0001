#pragma once
// The acoustic preset of an instrument as plain data: the modes of its bars and how the
// strike speed v sets the note's loudness and brightness. Loaded from
// config/instruments.toml by core/config/instruments_config; played by
// audio::ModalBarVoice (src/audio/modal_bar.hpp), which states the strike law.
#include <string>
#include <vector>

namespace mallet {

//! The most modes a preset may have (ModalBarVoice keeps a fixed array of this size).
inline constexpr int kMaxModalModes = 8;

//! One partial of a struck bar: a·e^(−decay·t)·sin(2π·ratio·f0·t).
struct Mode {
  double ratio = 1.0;        //!< frequency / fundamental (the first mode's is 1)
  double gain = 1.0;         //!< relative amplitude at the reference speed (see ModalPreset)
  double decay_per_s = 5.0;  //!< e^(−decay·t), in 1/s
};

//! The strike law (s = v / reference_speed_m_per_s, v the normal impact speed; v ≤ 0 → 0):
//!
//!   note amplitude  E(s) = loudness·s                                             s ≤ 1
//!                   E(s) = 1 − (1 − loudness)² / (1 − 2·loudness + loudness·s)    s > 1
//!   effective speed σ(s) = E(s) / loudness        (= s up to the reference, then < 1/loudness)
//!   brightening     c_k  = min(4, σ^(brightness·(ratio_k − 1)/ratio_k))         (c_1 = 1)
//!   mode k          a_k  = E · gain_k·c_k / Σ_j gain_j·c_j
//!
//! E is 0 at rest and linear up to the reference speed, where the note's amplitude is
//! `loudness`; above it a rational knee with the same slope compresses it towards full
//! scale 1, which no finite speed reaches: since Σ a_k = E, |note| ≤ E < 1 (v = 100 m/s
//! included). c_k grows with speed for every overtone (ratio > 1), the faster the higher
//! the mode — a harder, shorter contact excites higher modes — so the overtones' share of
//! the note grows with v. The brightening follows the compressed speed σ, not s, so the
//! timbre saturates with the loudness: with brightness ≤ 1 no partial ever gets quieter
//! when the strike gets harder (every a_k is non-decreasing in v). The sums run over all
//! configured modes, so a mode left out near Nyquist does not change the others.
struct ModalPreset {
  std::string name;
  std::vector<Mode> modes;               //!< 1 .. kMaxModalModes; modes[0].ratio == 1
  double loudness = 0.25;                //!< E at the reference speed, full scale = 1; in [0, 1]
  double reference_speed_m_per_s = 2.0;  //!< > 0
  double brightness = 1.0;               //!< in [0, 1]; 0 = the same timbre at every speed
  //! How many of the modes sound (the lowest ones; a quality knob, audio.max_modes). The
  //! strike law's sums still run over all modes, so the modes kept sound exactly as with
  //! all of them and the note only loses the ones left out.
  int max_sounding_modes = kMaxModalModes;
};

}  // namespace mallet
