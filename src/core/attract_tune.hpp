#pragma once
// The attract mode's tune: what the ghost player strikes when nobody is playing. A tune a
// passer-by knows on each instrument, the first line of Beethoven's "Ode to Joy" on the
// xylophone answered by "Twinkle, Twinkle, Little Star" on the glockenspiel, phrased with
// soft and hard strikes, so that they see (and hear and, holding the stick, feel) both
// materials and how a strike's speed changes the bounce, the note and the actuator.
#include <vector>

#include "core/ghost_player.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"

namespace mallet {

struct AttractTune {
  double beat_s = 0.42;        //!< time between strikes
  double rest_beats = 4;       //!< silence after the phrase before it repeats
  double speed_m_per_s = 1.2;  //!< mezzo-forte; the phrasing plays from half of it to 1.6 times it
};

//! The phrase's strikes starting at `start_ns`: on each instrument (left to right in the
//! scene) its tune, the first instrument "Ode to Joy" (E E F G G F E D C C D E E D D), the
//! next "Twinkle, Twinkle" (C C G G A A G F F E E D D C), then again in turn; a note's
//! degree is its bar in the row (an octave from C), as far as the instrument has bars (a
//! wall taps its one target in the tune's rhythm). Empty for a scene without instruments.
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
