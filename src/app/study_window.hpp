#pragma once
// `mallet study` with a display: the participant's session in a window (fullscreen unless
// windowed) on the monotonic clock. Each trial's taps go through the same StudyStimuli path
// as the headless run — the bounce drawn by the scene renderer at each frame's predicted
// present time, the actuator and the sound on the audio device (silent when there is
// none) — then a prompt asks for the answer, taken from the keys (1/2, or a material's
// letter); the response time runs from the end of the last tap. Esc, Q or closing the
// window stops: the rows already written stay, and a new run resumes.
#include <string>

#include "app/study_session.hpp"

namespace mallet::app {

struct StudyWindowOptions {
  bool windowed = false;        //!< a window instead of fullscreen
  std::string size = "1280x720";
  std::string device;           //!< Vulkan device name substring; empty: the settings'
  double quit_after_s = 0;      //!< test hook: stop (as Esc) after this long; 0 = never
};

//! Same errors as run_study (the answers come from the keys: StudyOptions::answers and
//! ::audio are not used). `validation_failed`: Vulkan validation reported a message.
StudyRunResult run_study_window(const StudyOptions& options, const StudyWindowOptions& window,
                                bool& validation_failed);

}  // namespace mallet::app
