#pragma once
// A MIDI note's name as a visitor reads it on a bar: the letter, a sharp as "#" (the
// overlay's font is Latin-1), and the octave in scientific pitch notation (MIDI 60 = C4).
#include <string>

namespace mallet {

inline std::string note_name(int midi_note) {
  static constexpr const char* kNames[] = {"C", "C#", "D", "D#", "E", "F", "F#", "G", "G#", "A", "A#", "B"};
  const int octave = (midi_note >= 0 ? midi_note / 12 : (midi_note - 11) / 12) - 1;
  const int pitch = ((midi_note % 12) + 12) % 12;
  return kNames[pitch] + std::to_string(octave);
}

}  // namespace mallet
