#pragma once
// The words over the visitors' screen in the attract mode and play, drawn in one place for
// the kiosk's window and its headless run: each bar's note name, the wall's plaque, the one
// line at the top (a hint, the study's offer, a notice), the offer's "Yes" sign and the
// staff's corner notes. Nothing of it shows over the operator page or the calibration,
// which have their own. What it draws keeps the overlap contract: no text over another, none
// off the screen, at every shape and in every language (tests/app/kiosk/text_boxes_test.cpp).
#include <optional>
#include <string>

#include "core/scene.hpp"
#include "render/overlay.hpp"
#include "render/overlay_text.hpp"

namespace mallet::app {

struct VisitorWords {
  bool note_names = false;                     //!< [visual] note_names: each bar's name on it
  std::string wall_name;                       //!< the wall's material on its plaque ("": none)
  std::string banner;                          //!< the line at the top ("": none)
  std::optional<render::BarLabel> called_out;  //!< the study offer's "Yes", a sign under its bar
  std::string staff_left, staff_right;         //!< corner notes for the staff ("": none)
};

//! `words` over `scene` (as laid out for the screen) on a width×height screen.
void draw_visitor_words(render::Overlay& overlay, const Scene& scene, const VisitorWords& words, float width,
                        float height);

}  // namespace mallet::app
