#include "app/kiosk_text.hpp"

#include <cstdio>

#include "app/simulate.hpp"
#include "core/note_name.hpp"
#include "render/scene_view.hpp"

namespace mallet::app {

std::string strike_line(const Scene& scene, const Impact& i) {
  const Target& t = scene.targets.at(i.target);
  char buf[224];
  const std::size_t m = static_cast<std::size_t>(i.material);
  const char* material = i.material >= 0 && m < scene.materials.size() ? scene.materials[m].name.c_str() : "?";
  std::snprintf(buf, sizeof buf, "strike t=%s bar=%d %s note=%d speed=%.3f m/s material=%s",
                format_seconds(i.t_ns).c_str(), t.id, t.instrument.c_str(), t.note, i.speed_m_per_s, material);
  return buf;
}

void draw_banner(render::Overlay& overlay, std::string_view text, float width, float height) {
  const render::FontAtlas& font = overlay.atlas();
  const float px = font.pixel_height();
  const float w = font.measure(text) + 2 * px, h = px * 1.8f;
  const float x = (width - w) / 2, y = height * 0.08f;
  overlay.fill_rect(x, y, w, h, {0.0f, 0.0f, 0.0f, 0.55f});
  overlay.text(width / 2, y + h / 2 + px * 0.35f, text, {1.0f, 1.0f, 1.0f, 1.0f}, render::TextAlign::center);
}

void draw_note_names(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height) {
  if (scene.kind != SceneKind::percussion) return;
  const float px = overlay.atlas().pixel_height();
  for (const Target& t : scene.targets) {
    // On the bar's top, a little in from its near end (the end towards the visitor).
    const glm::dvec3 at{(t.x_min + t.x_max) / 2, t.top_y, t.length_m / 2 - 0.03};
    const glm::dvec2 s = render::project_to_screen(view_proj, at);
    const std::string name = note_name(t.note);
    const float x = static_cast<float>(s.x) * width, y = static_cast<float>(s.y) * height;
    const float w = overlay.atlas().measure(name) + px * 0.4f;
    overlay.fill_rect(x - w / 2, y - px * 0.95f, w, px * 1.2f, {0.0f, 0.0f, 0.0f, 0.45f});
    overlay.text(x, y, name, {1.0f, 1.0f, 1.0f, 0.95f}, render::TextAlign::center);
  }
}

}  // namespace mallet::app
