#pragma once
#include <cmath>

namespace mallet {

//! Equal temperament: MIDI note 69 is A4 at `a4_hz` (440 Hz by default).
inline double note_frequency_hz(int midi_note, double a4_hz = 440.0) {
  return a4_hz * std::exp2((midi_note - 69) / 12.0);
}

}  // namespace mallet
