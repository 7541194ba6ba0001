#pragma once
// The operator page (behind Ctrl+Alt+O): what its keys do, its panel of status lines, and
// its D view, `mallet doctor`'s checks with what the kiosk knows of the devices it holds.
// The kiosk (window_kiosk.cpp) gathers the lines and carries the actions out.
#include <string>
#include <utility>
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
  next_page,      //!< Page Down: the page's next screen, when it takes more than one
  previous_page,  //!< Page Up
};

//! What a key (GLFW's key and modifiers) does: the chord opens the page anywhere; the
//! page's keys act only while it is open (`page_open`); a visitor's keys do nothing.
OperatorAction operator_action(int key, int mods, bool page_open);

//! Whether a held key's auto-repeat does the action again: only a step (the volume, the
//! gain). A held chord must not open and close the page again and again (a remote desktop or
//! a slow frame holds keys for seconds), nor a held key quit, reload or switch twice.
bool operator_action_repeats(OperatorAction action);

//! How a line of the operator page is set.
enum class PageTone {
  title,    //!< the page's first line, bright
  status,   //!< what runs and how
  warning,  //!< what needs the operator: "!" in the mark column, amber; listed first
  fail,     //!< a doctor's check (D): its level in the mark column, red ...
  warn,     //!< ... amber ...
  ok,       //!< ... or green
  keys,     //!< the keys' line ("D back to the page    Esc close"): last, on every screen of a page that takes several
};

//! One line of the page: it wraps within the panel and is never cut.
struct PageLine {
  PageLine(PageTone t, std::string line, std::string name = {})
      : tone(t), text(std::move(line)), head(std::move(name)) {}
  bool operator==(const PageLine&) const = default;
  PageTone tone = PageTone::status;
  std::string text;  //!< '\n' starts a continuation row (a check's fix)
  std::string head;  //!< a doctor's check's name, set in a column of its own; empty: none
};

//! A text of the page, placed: its left edge and baseline in pixels.
struct PageRow {
  float x = 0, y = 0;
  std::string text;
  PageTone tone = PageTone::status;
};

//! The page laid out for a screen: a translucent panel, the text's size and every row placed.
struct PageLayout {
  float x = 0, y = 0, width = 0, height = 0;  //!< the panel
  float scale = 1;                            //!< the text's size: a share of the font atlas's
  std::vector<PageRow> rows;
  int page = 0, pages = 1;  //!< which of the page's screens this is (PgDn: the next)
};

//! Lays the page out for a `width` × `height` screen. The text is set at most 3/4 of the
//! visitors' size, smaller (down to half) until every line fits the screen's height, and on
//! screens taken in turn (PgDn, `page`: which one, wrapping) when even that does not; lines
//! never split across two screens, and the warnings come first. Lines wrap at a semicolon, a
//! comma, before a parenthesis or between two keys' entries, else at a space, onto indented
//! continuation rows; a check's level and name (D) stand in columns of their own, its text
//! wrapping beside them. `clear_corner`: the side of a square at the top-left corner the
//! panel keeps clear of (the latency test's; 0: none): moved right, else laid out again in
//! the height below the square.
PageLayout layout_operator_page(const render::FontAtlas& font, const std::vector<PageLine>& lines, float width,
                                float height, float clear_corner = 0, int page = 0);

//! Draws a laid-out page: the panel, each row in its tone's colour (every one ≥ 4.5:1 on
//! the panel), a check's level and a warning's "!" in their mark column.
void draw_operator_page(render::Overlay& overlay, const PageLayout& layout);

//! Operator page D: `mallet doctor`'s checks, with what the kiosk knows of the devices it
//! holds (its renderer at `frame_ms` a frame, its audio output and its remote) instead of
//! opening them again, and why its last write into the state folder failed (`state_problem`;
//! empty: it did not). Returns the page's lines (what was found, and the fix of a check that
//! is not ok); the journal gets each check whole, with its fix.
std::vector<PageLine> doctor_page_lines(const KioskStage& stage, const render::ProductWindow& window,
                                           const KioskOptions& options, double frame_ms,
                                           const std::string& state_problem);

}  // namespace mallet::app
