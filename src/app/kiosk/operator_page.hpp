#pragma once
// The operator page (behind Ctrl+Alt+O): what its keys do, its panel of status lines, and
// its D view, `mallet doctor`'s checks with what the kiosk knows of the devices it holds.
// The kiosk (window_kiosk.cpp) gathers the lines and carries the actions out.
#include <string>
#include <vector>

#include "app/kiosk/kiosk.hpp"
#include "app/kiosk/kiosk_stage.hpp"
#include "render/overlay.hpp"
#include "render/render_setup.hpp"

namespace mallet::app {

enum class OperatorAction {
  none,
  open,         //!< Ctrl+Alt+O, anywhere
  close,        //!< Esc
  quit,         //!< Q
  recalibrate,  //!< R
  volume_up,    //!< Up
  volume_down,  //!< Down
  gain_up,      //!< Right: the actuator's gain
  gain_down,    //!< Left
  next_material,  //!< M: the wall's next material
  next_scene,     //!< S: the next of [scenes] choices
  next_language,  //!< L
  latency_test,   //!< T
  doctor,         //!< D: the doctor's checks, or back to the page
};

//! What a key (GLFW's key and modifiers) does: the chord opens the page anywhere; the
//! page's keys act only while it is open (`page_open`); a visitor's keys do nothing.
OperatorAction operator_action(int key, int mods, bool page_open);

//! Whether a held key's auto-repeat does the action again: only a step (the volume, the
//! gain). A held chord must not open and close the page again and again (a remote desktop or
//! a slow frame holds keys for seconds), nor a held key quit, reload or switch twice.
bool operator_action_repeats(OperatorAction action);

//! The page's lines on a centred translucent panel, the first bright. Long lines wrap at a
//! semicolon, a comma, before a parenthesis or between two keys' entries onto indented
//! continuation lines, else at a space; in the `doctor` view each line is cut to the panel
//! (the whole line is in the journal). `clear_corner`: the side of a square at the top-left
//! corner the panel keeps clear of (the latency test's; 0: none): moved right, else down.
void draw_operator_page(render::Overlay& overlay, const std::vector<std::string>& lines, bool doctor, float width,
                        float height, float clear_corner = 0);

//! Operator page D: `mallet doctor`'s checks, with what the kiosk knows of the devices it
//! holds (its renderer at `frame_ms` a frame, its audio output and its remote) instead of
//! opening them again, and why its last write into the state folder failed (`state_problem`;
//! empty: it did not). Returns the page's lines (what was found); the journal gets each
//! check whole, with its fix.
std::vector<std::string> doctor_page_lines(const KioskStage& stage, const render::ProductWindow& window,
                                           const KioskOptions& options, double frame_ms,
                                           const std::string& state_problem);

}  // namespace mallet::app
