#pragma once
// What the product shows in words over the scene, shared by the kiosk's window, its headless
// run and the study: the one-line banner (the invitation, the hints) and the bars' labels.
#include <string>
#include <string_view>
#include <vector>

#include "core/impact.hpp"
#include "core/scene.hpp"
#include <glm/glm.hpp>

#include "render/overlay.hpp"

namespace mallet::render {

//! A text's band on the screen, in pixels.
struct NoteBox {
  float x = 0, y = 0, width = 0, height = 0;
};

//! The text centred near the top of a width×height screen, on a translucent band; wrapped
//! onto more lines where one would not fit the screen's width (render/text_wrap.hpp).
//! Returns the band.
NoteBox draw_banner(render::Overlay& overlay, std::string_view text, float width, float height);

enum class Corner { bottom_left, bottom_right };
//! A small note for the staff in a bottom corner ("Mouse", "No sound", a refused close):
//! smaller than the visitors' words, discreet, on a dark band of its own, so that it reads
//! (at least 4.5:1, WCAG 2.1 AA) over every scene, the grey texture scene's too.
NoteBox draw_corner_note(render::Overlay& overlay, std::string_view text, Corner corner, float width, float height);

//! A label on a bar: its near end, as `view_proj` shows the bar on a width×height image, on
//! a small translucent band so it reads on wood and metal alike.
struct BarLabel {
  int target = 0;
  std::string text;
};
void draw_bar_labels(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height, const std::vector<BarLabel>& labels);

//! A sign under a bar: `text` at the visitors' size (the banner's letters), centred on the
//! bar, on a band just below its near end (the end towards the visitor) as `view_proj` shows
//! it, so that it reads from two metres away and never covers the bar's own note name; kept
//! on the screen and above the corner notes' row. The study's answer bars ("Yes", "No", "1",
//! "Taps") carry them on a dark band; a called-out sign (the offer's "Yes" on the kiosk's
//! instrument, where the ghost keeps playing beside it) on a bright amber one. Returns each
//! sign's band.
enum class SignStyle { plain, called_out };
std::vector<NoteBox> draw_bar_signs(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj,
                                    float width, float height, const std::vector<BarLabel>& signs,
                                    SignStyle style = SignStyle::plain);

//! The wall's material by name ("Wood", "Rubber") on a plaque at the foot of the wall, as
//! `view_proj` shows it, on a dark band: the three walls look alike by design (the paper's white rectangle), so
//! the name says which one a visitor taps and which one the operator's M chose.
NoteBox draw_wall_name(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                       float height, std::string_view name);

//! Each bar's note name ([visual] note_names) on its near end, as `view_proj` shows the bar
//! on a width×height image, on a small translucent band so it reads on wood and metal alike.
void draw_note_names(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height);

}  // namespace mallet::render
