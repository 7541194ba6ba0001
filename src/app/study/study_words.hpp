#pragma once
// The words over a study's screen (`mallet study --window`, and the kiosk's visitor study):
// the line at the top (the consent, a trial's prompt, "Tap 1", "Thank you"), the signs under
// the answer bars ("Yes", "No", "1", "2", "Taps") and the trial count in the bottom corner.
// Drawn in one place, so that the overlap contract's test draws what the window draws: no
// text over another, none off the screen (tests/app/study/study_words_test.cpp).
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "render/overlay.hpp"
#include "render/overlay_text.hpp"

namespace mallet::app {

struct StudyWords {
  std::string banner;                     //!< the line at the top ("": none)
  std::vector<render::BarLabel> signs;    //!< under the study scene's bars
  std::string status;                     //!< "Trial 2 of 6", discreet, bottom left ("": none)
};

//! `words` over the study scene `scene` (as laid out for the screen) on a width×height screen.
void draw_study_words(render::Overlay& overlay, const Scene& scene, const StudyWords& words, float width,
                      float height);

}  // namespace mallet::app
