#pragma once
// What one voice costs per sample, timed the same way by `bench audio` and `bench report`:
// the median over a few runs of the wall time per unit of work. A benchmark's figure,
// printed in a table, never asserted by a test.
#include <functional>
#include <optional>

#include "core/modal_preset.hpp"
#include "core/vibration.hpp"

namespace mallet::app {

//! Median over `runs` of the nanoseconds per unit of `body`, which does `units` units.
double median_ns_per_unit(int runs, double units, const std::function<void()>& body);

//! Keeps the optimiser from removing the measured work: a body hands its result here.
void keep(double value);

//! Eq. 1 evaluated directly (exp + sin per sample) for `n` samples at `rate_hz`: ns per sample.
double direct_eq1_ns(const VibrationParams& eq1, int n, int rate_hz, int runs);

//! The engine's actuator voice (audio::DampedOscillator, a re-seeded rotator) at
//! `frequency_hz`, undamped so that it never goes quiet: ns per sample.
double rotator_ns(double frequency_hz, int n, int rate_hz, int runs);

//! One modal bar voice of `preset` striking `fundamental_hz` at 1.5 m/s: ns per sample.
double modal_bar_ns(const ModalPreset& preset, double fundamental_hz, int n, int rate_hz, int runs);

//! The peer STK's ModalBar (its vibraphone preset, 4 modes and a strike sample) striking
//! C5: ns per sample; nothing when Mallet is built without STK.
std::optional<double> stk_modal_bar_ns(int n, int rate_hz, int runs);

//! The peer FluidSynth with the shipped General MIDI soundfont, 16 notes sounding: ns per
//! voice-frame. Throws when FluidSynth or the soundfont cannot start.
double fluidsynth_ns_per_voice_frame(int n, int rate_hz, int runs);

}  // namespace mallet::app
