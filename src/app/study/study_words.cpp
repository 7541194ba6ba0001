#include "app/study/study_words.hpp"

#include "render/scene_view.hpp"

namespace mallet::app {

void draw_study_words(render::Overlay& overlay, const Scene& scene, const StudyWords& words, float width,
                      float height) {
  if (!words.signs.empty())
    render::draw_bar_signs(overlay, scene, render::view_projection(scene, width / height), width, height, words.signs);
  if (!words.banner.empty()) render::draw_banner(overlay, words.banner, width, height);
  if (!words.status.empty()) {
    const float px = overlay.atlas().pixel_height();
    overlay.text(px, height - px, words.status, {1.0f, 1.0f, 1.0f, 0.35f});
  }
}

}  // namespace mallet::app
