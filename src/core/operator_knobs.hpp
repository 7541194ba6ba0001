#pragma once
// The operator page's two knobs, the volume and the actuator gain (the paper's amplifier
// knob, in software): each arrow key moves one step toward its end of the range the settings
// allow ([audio] volume 0..4, shown as 0..400 %; [actuator] gain 0..10), and never the other
// way: a kiosk set above the old 100 % cap must not be turned down by Up.
//
// One source for both: the settings loader reads [audio] volume and [actuator] gain within
// these same ranges, so the page, the file and docs/operators.md cannot disagree. No value in
// them clips: the engine's output limiter (audio/peak_limiter.hpp) keeps both channels under
// full scale.
#include <algorithm>

namespace mallet {

struct KnobRange {
  double lo, hi, step;
};

inline constexpr KnobRange kVolumeKnob{0.0, 4.0, 0.05};  //!< [audio] volume's range (the loader's too)
inline constexpr KnobRange kGainKnob{0.0, 10.0, 0.02};   //!< [actuator] gain's range (the loader's too)

//! One step up (`up`) or down, within the range; a value already past an end is left there.
inline double knob_step(double value, const KnobRange& k, bool up) {
  return up ? std::max(value, std::min(k.hi, value + k.step)) : std::min(value, std::max(k.lo, value - k.step));
}

}  // namespace mallet
