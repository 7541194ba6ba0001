#include "render/overlay_text.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "core/note_name.hpp"
#include "render/scene_view.hpp"
#include "render/text_wrap.hpp"

namespace mallet::render {

void draw_banner(render::Overlay& overlay, std::string_view text, float width, float height) {
  const render::FontAtlas& font = overlay.atlas();
  const float px = font.pixel_height();
  // As many lines as the screen's width needs (a portrait screen, a long language), each
  // centred and about as long as each other; the band as wide as the widest.
  std::vector<std::string> lines = render::wrap_text(font, text, width - 4 * px);
  if (lines.size() > 1) {  // balanced: the narrowest width that still needs no more lines
    float lo = font.measure(text) / static_cast<float>(lines.size()), hi = width - 4 * px;
    for (int i = 0; i < 12; ++i) {
      const float mid = (lo + hi) / 2;
      (render::wrap_text(font, text, mid).size() > lines.size() ? lo : hi) = mid;
    }
    lines = render::wrap_text(font, text, hi);
  }
  float widest = 0;
  for (const std::string& l : lines) widest = std::max(widest, font.measure(l));
  const float line = px * 1.3f;
  const float w = widest + 2 * px, h = px * 1.8f + line * static_cast<float>(lines.size() > 1 ? lines.size() - 1 : 0);
  const float x = (width - w) / 2, y = height * 0.08f;
  overlay.fill_rect(x, y, w, h, {0.0f, 0.0f, 0.0f, 0.55f});
  for (std::size_t i = 0; i < lines.size(); ++i)
    overlay.text(width / 2, y + px * 0.9f + px * 0.35f + line * static_cast<float>(i), lines[i],
                 {1.0f, 1.0f, 1.0f, 1.0f}, render::TextAlign::center);
}

void draw_bar_labels(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height, const std::vector<BarLabel>& labels) {
  const float px = overlay.atlas().pixel_height();
  for (const BarLabel& label : labels) {
    const Target& t = scene.targets.at(static_cast<std::size_t>(label.target));
    // On the bar's top, a little in from its near end (the end towards the visitor).
    const glm::dvec3 at{(t.x_min + t.x_max) / 2, t.top_y, t.length_m / 2 - 0.03};
    const glm::dvec2 s = render::project_to_screen(view_proj, at);
    const float x = static_cast<float>(s.x) * width, y = static_cast<float>(s.y) * height;
    const float w = overlay.atlas().measure(label.text) + px * 0.4f;
    overlay.fill_rect(x - w / 2, y - px * 0.95f, w, px * 1.2f, {0.0f, 0.0f, 0.0f, 0.45f});
    overlay.text(x, y, label.text, {1.0f, 1.0f, 1.0f, 0.95f}, render::TextAlign::center);
  }
}

void draw_note_names(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height) {
  if (scene.kind != SceneKind::percussion) return;
  std::vector<BarLabel> labels;
  for (const Target& t : scene.targets) labels.push_back({t.id, note_name(t.note)});
  draw_bar_labels(overlay, scene, view_proj, width, height, labels);
}

}  // namespace mallet::render
