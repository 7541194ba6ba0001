#pragma once
// `mallet bench render`'s text table: what the overlay's text costs in each script, a page of
// every text of the kiosk's catalogue (Latin, Arabic, Devanagari) over the scene.
#include <string>

namespace mallet::app {

//! Prints the table: per language, the first frame's overlay (every text set, every glyph
//! drawn), a later one's (all kept), the frame with and without it, and the texts set.
void print_text_costs(const std::string& device, int frames);

}  // namespace mallet::app
