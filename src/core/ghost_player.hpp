#pragma once
// A scripted player: the hand path that strikes a sequence of bars at given times and
// speeds. It is the attract mode's "ghost player", and the researchers' way to script
// exact strikes (`mallet trajectory`): each strike crosses the bar's contact plane at
// exactly its time with exactly its downward speed.
#include <vector>

#include "core/pointer_sample.hpp"
#include "core/scene.hpp"

namespace mallet {

struct ScriptedStrike {
  int target = 0;              //!< Target::id
  Nanos t_ns = 0;              //!< when the sphere meets the bar
  double speed_m_per_s = 1.5;  //!< downward speed at contact
};

struct GhostPlayerStyle {
  double hover_height_m = 0.08;  //!< sphere bottom above the bar between strikes
  double follow_through_m = 0.004;  //!< how far the hand goes below the surface
  double lift_speed_m_per_s = 0.6;
};

struct GhostPath {
  std::vector<PointerSample> samples;  //!< the hand: sphere centre, world metres
  std::vector<Nanos> contacts;         //!< when each strike really meets its bar
};

//! The hand sampled at `rate_hz` from the first strike's approach to the last strike's
//! lift. Strikes must be in time order and leave enough time between them to lift and
//! travel (at 1 m/s); otherwise the path arrives late and the strike happens when it
//! arrives (still one impact each): `contacts` says when.
GhostPath ghost_player(const Scene& scene, const std::vector<ScriptedStrike>& strikes, double rate_hz,
                       const GhostPlayerStyle& style = {});

}  // namespace mallet
