#pragma once
// `mallet study` with a display: the participant's session in a window (fullscreen unless
// windowed) on the monotonic clock. Each trial's taps go through the same StudyStimuli path
// as the headless run — the bounce drawn by the scene renderer at each frame's predicted
// present time, the actuator and the sound on the audio device (silent when there is
// none) — then a prompt asks for the answer, taken from the keys (1/2, or a material's
// letter); the response time runs from the end of the last tap. Esc, Q or closing the
// window stops: the rows already written stay, and a new run resumes.
#include <functional>
#include <string>
#include <vector>

#include "render/render_setup.hpp"
#include "app/study/study_session.hpp"
#include "app/study/visitor_study.hpp"
#include "core/pointer_sample.hpp"

namespace mallet::app {

struct StudyWindowOptions {
  bool windowed = false;        //!< a window instead of fullscreen
  std::string size = "1280x720";
  std::string device;           //!< Vulkan device name substring; empty: the settings'
  double quit_after_s = 0;      //!< test hook: stop (as Esc) after this long; 0 = never
};

//! Same errors as run_study (the answers come from the keys: StudyOptions::answers and
//! ::audio are not used); `validation_failed` when Vulkan validation reported a message.
StudyRunResult run_study_window(const StudyOptions& options, const StudyWindowOptions& window);

//! A visitor's session (visitor_study.hpp) in the kiosk's own window `win`: the consent
//! screen and the trials, answered by striking; "Thank you" for 3 s after the last. The
//! window's key and cursor callbacks and user pointer are the study's until it returns (the
//! caller sets its own again). `pointer`: the kiosk's pointer samples (normalised screen)
//! since the last call, or empty for the window system's cursor; `each_frame`: called once a
//! frame (the kiosk feeds its watchdog), false to stop (the kiosk was asked to). Esc and Q do not stop a visitor's session; no strike for the protocol's
//! answer_timeout_s does (the visitor walked away).
study::VisitorSessionResult run_visitor_window(render::ProductWindow& win, const StudyPlan& plan,
                                        std::function<std::vector<PointerSample>()> pointer = {},
                                        std::function<bool()> each_frame = {});

}  // namespace mallet::app
