#pragma once
// How a study stimulus reaches the participant through the kiosk's own code: each
// stimulus × condition becomes a bar of a study scene — a copy of the protocol's
// reference bar (so the note, if any, is the same for every stimulus) — whose material
// keeps only what the condition presents: visual_only zeroes the actuator triple's A,
// tactile_only the visual one, none both. A tap is then an Impact on that bar: the audio
// engine plays Eq. 1 on the actuator channel and the strike loop bounces the mallet with
// Eq. 1, exactly as for a visitor's strike. The stimulus bars are all in the reference
// bar's place and only the program strikes them (Target::hand_strikes); the speaker plays
// their note only when the protocol's `sound` says so (Instrument::speaker).
//
// With response = "strike" the scene also has one answer bar per answer choice, in its
// order: a bar of the reference's shape on its own rails, spread beside the stimulus bar,
// struck by the participant's mallet. An answer strike sounds the protocol's
// answer_strike voice (a neutral click) and carries its `feel` (none by default: no
// actuator signal, no bounce).
#include <string>
#include <vector>

#include "core/impact.hpp"
#include "core/scene.hpp"
#include "core/study/study_protocol.hpp"

namespace mallet::app {

Scene make_study_scene(const Scene& base, const study::StudyProtocol& protocol);

//! The study scene as a window of `aspect` (width over height) shows it. On a portrait
//! screen (aspect < 1) the answer bars stand close beside each other in their order, then
//! the stimulus bar on the right, and the scene is narrowed to them: a band of large bars
//! across the screen's width, not small ones in a band across its middle (the answers
//! left of where the kiosk's offer had its "Yes"). A landscape or unknown (0) aspect, a
//! texture protocol and answers by keys: as made. `right_to_left` (the study shown in Arabic,
//! Hebrew): the answer bars' places mirrored among themselves, so that the first answer
//! ("Yes", "1") is the first read, on the right; the stimulus bar stays where it is.
Scene study_scene_for(const Scene& base, const study::StudyProtocol& protocol, double aspect,
                      bool right_to_left = false);

//! The answer bars of a study scene and the answer each gives, in the protocol's order of
//! answer_choices(); empty unless response = "strike".
struct AnswerBar {
  int target = 0;
  std::string answer;
};
std::vector<AnswerBar> answer_bars(const Scene& study_scene, const study::StudyProtocol& protocol);

//! texture_slope: the texture scene one crossing presents: `base` with the stimulus's relief
//! (shape and height), the Speed technique off (slope_gain 0: the cursor follows the hand)
//! unless the condition shows the visual cue, the stripes off (amplitude 0) unless it plays
//! the tactile one.
Scene texture_trial_scene(const Scene& base, const study::Stimulus& stimulus, study::StudyCondition condition);

//! The tap presenting `stimulus` (index in protocol.stimuli) under `condition` at t.
Impact stimulus_impact(const Scene& study_scene, const study::StudyProtocol& protocol, int stimulus,
                       study::StudyCondition condition, Nanos t);

}  // namespace mallet::app
