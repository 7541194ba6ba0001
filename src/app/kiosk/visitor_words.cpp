#include "app/kiosk/visitor_words.hpp"

#include "render/scene_view.hpp"

namespace mallet::app {

void draw_visitor_words(render::Overlay& overlay, const Scene& scene, const VisitorWords& words, float width,
                        float height) {
  const glm::mat4 view_proj = render::view_projection(scene, width / height);
  if (words.note_names) render::draw_note_names(overlay, scene, view_proj, width, height);
  if (!words.wall_name.empty()) render::draw_wall_name(overlay, scene, view_proj, width, height, words.wall_name);
  if (!words.banner.empty()) render::draw_banner(overlay, words.banner, width, height);
  if (words.called_out)
    render::draw_bar_signs(overlay, scene, view_proj, width, height, {*words.called_out},
                           render::SignStyle::called_out);
  if (!words.staff_left.empty())
    render::draw_corner_note(overlay, words.staff_left, render::Corner::bottom_left, width, height);
  if (!words.staff_right.empty())
    render::draw_corner_note(overlay, words.staff_right, render::Corner::bottom_right, width, height);
}

}  // namespace mallet::app
