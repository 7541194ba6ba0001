#pragma once
// Picks the Wii Remote IR camera's sensitivity preset that shows the stick's LED as exactly
// one clean dot (issue 6, the calibration screen's auto-adjust). Pure: the kiosk sets the
// camera to preset(), feeds the IR frames it then reports, and switches when told.
//
// Rule: presets are tried in kSensitivityPresets order, least sensitive first (wii1 … max),
// each for frames_per_preset frames after settle_frames (the camera taking its new blocks).
// A preset is clean when, over its frames:
//  * the LED is seen steadily: at least min_seen_fraction of the frames have a dot;
//  * no spurious dot: at most max_spurious_fraction of the frames (default none) have two or
//    more dots (a reflection, a lamp, sunlight);
//  * the dot's size is in range: the median size of the single-dot frames is within
//    min_size..max_size (extended mode; in basic mode there is no size and this is skipped).
// The first clean preset is chosen: the lowest sensitivity that sees the LED steadily, which
// keeps reflections, that grow with sensitivity, out. If none is clean the tuner fails and
// the kiosk keeps its configured preset. Slots that are the spurious (0,0) dot some remotes
// report, or lie off the sensor, are not dots (as in IrTracker).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/ir_camera_settings.hpp"
#include "core/ir_dot.hpp"
#include "core/result.hpp"

namespace mallet {

struct SensitivityTunerConfig {
  int settle_frames = 10;               //!< ignored after each switch
  int frames_per_preset = 100;          //!< judged per preset (≈ 1 s at 100 reports/s)
  double min_seen_fraction = 0.95;      //!< frames with a dot, at least
  double max_spurious_fraction = 0.0;   //!< frames with ≥ 2 dots, at most
  int min_size = 2;                     //!< median single-dot size range (camera's 0..15)
  int max_size = 8;
};

//! Passes when `config` is usable; otherwise fails with one line naming the bad key and why.
Check validate(const SensitivityTunerConfig& config);

//! What one preset showed.
struct SensitivityObservation {
  int frames = 0;
  int frames_seen = 0;      //!< frames with at least one dot
  int frames_spurious = 0;  //!< frames with two or more dots
  std::vector<int> sizes;   //!< the dot's size in each single-dot frame that has one
};

//! Counts one frame into `observation`.
void observe_frame(SensitivityObservation& observation, const IrFrame& frame);

struct SensitivityVerdict {
  bool clean = false;
  int median_size = -1;  //!< -1 without sizes (basic mode)
  std::string reason;    //!< why not clean; empty when clean
};

SensitivityVerdict judge(const SensitivityObservation& observation, const SensitivityTunerConfig& config);

enum class TunerStep {
  observing,    //!< keep the camera as it is
  next_preset,  //!< set the camera to preset() now
  chosen,       //!< done: chosen() is the preset to use
  failed,       //!< done: no preset was clean; verdicts() say why
};

class SensitivityTuner {
 public:
  struct Tried {
    std::string_view preset;
    SensitivityVerdict verdict;
  };

  //! Throws std::invalid_argument when validate(config) fails.
  explicit SensitivityTuner(SensitivityTunerConfig config = {});

  //! One IR frame reported while the camera ran preset().
  TunerStep observe(const IrFrame& frame);
  //! A whole preset's observation at once (e.g. gathered elsewhere): judges preset() by it.
  TunerStep observe(const SensitivityObservation& observation);

  //! What the camera must run now; the chosen one once chosen; empty after a failure (the
  //! kiosk then puts back its configured preset).
  std::string_view preset() const;
  bool done() const { return done_; }
  std::optional<std::string_view> chosen() const { return chosen_; }
  const std::vector<Tried>& verdicts() const { return tried_; }

 private:
  TunerStep conclude(const SensitivityObservation& observation);

  SensitivityTunerConfig config_;
  std::size_t index_ = 0;
  int settled_ = 0;
  SensitivityObservation current_;
  bool done_ = false;
  std::optional<std::string_view> chosen_;
  std::vector<Tried> tried_;
};

}  // namespace mallet
