#pragma once
// The attract mode's tune: what the ghost player strikes when nobody is playing. A
// short phrase that walks up the xylophone and answers on the glockenspiel, so a
// passer-by sees (and hears and, holding the stick, feels) both materials.
#include <vector>

#include "core/ghost_player.hpp"
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

}  // namespace mallet
