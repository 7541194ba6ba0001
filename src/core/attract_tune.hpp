#pragma once
// The attract mode's tune: what the ghost player strikes when nobody is playing. A
// short phrase that walks up the xylophone and answers on the glockenspiel, so a
// passer-by sees (and hears and, holding the stick, feels) both materials.
#include <vector>

#include "core/ghost_player.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"

namespace mallet {

struct AttractTune {
  double beat_s = 0.42;        //!< time between strikes
  double rest_beats = 4;       //!< silence after the phrase before it repeats
  double speed_m_per_s = 1.2;  //!< every strike's speed (loud enough to feel)
};

//! The phrase's strikes starting at `start_ns`: on each instrument (left to right in
//! the scene) bars 0, 2, 4, 7, 4 of its row (C E G C' G for an octave from C), as far as
//! the instrument has bars. Empty for a scene without instruments.
std::vector<ScriptedStrike> attract_phrase(const Scene& scene, Nanos start_ns, const AttractTune& tune = {});

//! How long one phrase and its rest last.
Nanos attract_period(const Scene& scene, const AttractTune& tune = {});

//! The texture scene's ghost: the hand (world metres, in PointerSample's fields) sweeps
//! across the disc through its centre, left to right, then back a little higher, at
//! `speed` m/s, sampled at `rate_hz` from `start_ns`; then rests. Empty without a texture.
std::vector<PointerSample> attract_sweep(const Scene& scene, Nanos start_ns, double rate_hz,
                                         double speed_m_per_s = 0.12);
//! How long one sweep and its rest last (0 without a texture).
Nanos attract_sweep_period(const Scene& scene, double speed_m_per_s = 0.12);

}  // namespace mallet
