#pragma once
// One strike of the mallet on a target: what the audio thread and the renderer need.
// Trivially copyable so it can cross a lock-free ring to the audio callback.
#include <type_traits>

#include "core/time.hpp"

namespace mallet {

struct Impact {
  Nanos t_ns = 0;             //!< exact contact time (fraction of the swept segment)
  int target = -1;            //!< Target::id
  int material = -1;          //!< index in Scene::materials
  int note = 0;               //!< MIDI note number
  double speed_m_per_s = 0;   //!< normal impact speed v (after clamping)
  double x_m = 0;             //!< where along the bar's top the sphere touched
  //! Both audio channels are heard this long after t_ns: 0 = as soon as possible
  //! ([timing] align = "asap"); the strike route sets it for align = "picture".
  Nanos delay_ns = 0;
  bool predicted = false;     //!< decided from a prediction before the contact was seen
};

static_assert(std::is_trivially_copyable_v<Impact>);

}  // namespace mallet
