#include "render/overlay_text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/note_name.hpp"
#include "render/scene_view.hpp"
#include "render/text_wrap.hpp"

namespace mallet::render {

NoteBox draw_banner(render::Overlay& overlay, std::string_view text, float width, float height) {
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
  return {x, y, w, h};
}

namespace {

//! A band for `text` at `scale` of the atlas's size: the text's width plus one letter, one
//! and a half letters high; at (0, 0) until placed.
NoteBox band_for(const render::FontAtlas& font, std::string_view text, float scale) {
  const float em = font.pixel_height() * scale;
  return {0, 0, font.measure(text) * scale + em, em * 1.5f};
}

//! `text` at `scale`, centred on its dark band `box` (alpha `shade`), its baseline on a whole
//! pixel (crisp).
NoteBox draw_on_band(render::Overlay& overlay, const NoteBox& box, std::string_view text, float scale, float shade,
                     std::array<float, 4> colour) {
  const render::FontAtlas& font = overlay.atlas();
  overlay.fill_rect(box.x, box.y, box.width, box.height, {0.0f, 0.0f, 0.0f, shade});
  const float baseline = std::round(box.y + box.height / 2 + (font.ascent() - font.descent()) * scale / 2);
  overlay.text(box.x + box.width / 2, baseline, text, colour, render::TextAlign::center, scale);
  return box;
}

}  // namespace

NoteBox draw_corner_note(render::Overlay& overlay, std::string_view text, Corner corner, float width,
                         float height) {
  constexpr float kScale = 0.6f;  // discreet: 3/5 of the visitors' letters
  const float margin = overlay.atlas().pixel_height() * kScale * 0.5f;
  NoteBox box = band_for(overlay.atlas(), text, kScale);
  box.x = corner == Corner::bottom_left ? margin : width - margin - box.width;
  box.y = height - margin - box.height;
  return draw_on_band(overlay, box, text, kScale, 0.7f, {1.0f, 1.0f, 1.0f, 0.8f});
}

void draw_bar_labels(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height, const std::vector<BarLabel>& labels) {
  const render::FontAtlas& font = overlay.atlas();
  const float px = font.pixel_height();
  for (const BarLabel& label : labels) {
    const Target& t = scene.targets.at(static_cast<std::size_t>(label.target));
    // On the bar's top, a little in from its near end (the end towards the visitor): centred
    // between its two edges as the view shows them, and no wider than the bar, so that
    // neighbours never run together (a narrow glockenspiel, a portrait screen). Smaller
    // letters where the bar is narrow, down to 12 px (or 30 % of the visitors' size).
    const double z = t.length_m / 2 - 0.03;
    const glm::dvec2 left = render::project_to_screen(view_proj, {t.x_min, t.top_y, z});
    const glm::dvec2 right = render::project_to_screen(view_proj, {t.x_max, t.top_y, z});
    const float x = static_cast<float>((left.x + right.x) / 2) * width;
    const float y = std::round(static_cast<float>((left.y + right.y) / 2) * height);
    const float bar = static_cast<float>(std::abs(right.x - left.x)) * width;
    const float ink = font.measure(label.text);
    const float smallest = std::min(1.0f, std::max(0.3f, 12.0f / px));
    const float scale = std::clamp((bar * 0.92f) / (ink + px * 0.4f), smallest, 1.0f);
    const float w = (ink + px * 0.4f) * scale;
    overlay.fill_rect(x - w / 2, y - px * 0.95f * scale, w, px * 1.2f * scale, {0.0f, 0.0f, 0.0f, 0.45f});
    overlay.text(x, y, label.text, {1.0f, 1.0f, 1.0f, 0.95f}, render::TextAlign::center, scale);
  }
}

std::vector<NoteBox> draw_bar_signs(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj,
                                    float width, float height, const std::vector<BarLabel>& signs, SignStyle style) {
  const float em = overlay.atlas().pixel_height();
  std::vector<NoteBox> out;
  for (const BarLabel& sign : signs) {
    const Target& t = scene.targets.at(static_cast<std::size_t>(sign.target));
    const glm::dvec2 end = render::project_to_screen(view_proj, {(t.x_min + t.x_max) / 2, t.top_y - t.thickness_m,
                                                                 t.length_m / 2});
    NoteBox box = band_for(overlay.atlas(), sign.text, 1.0f);
    box.x = std::clamp(static_cast<float>(end.x) * width - box.width / 2, em * 0.5f,
                       std::max(em * 0.5f, width - em * 0.5f - box.width));
    // Below the near end, a quarter of a letter apart; never down into the corner notes' row
    // (draw_corner_note: 0.6 of a letter, on a band 1.5 of its letters high, half one in).
    box.y = std::min(std::round(static_cast<float>(end.y) * height + em * 0.25f), height - em * 1.3f - box.height);
    if (style == SignStyle::called_out) {
      overlay.fill_rect(box.x, box.y, box.width, box.height, {1.0f, 0.72f, 0.16f, 0.95f});
      out.push_back(draw_on_band(overlay, box, sign.text, 1.0f, 0.0f, {0.08f, 0.06f, 0.02f, 1.0f}));
    } else {
      out.push_back(draw_on_band(overlay, box, sign.text, 1.0f, 0.6f, {1.0f, 1.0f, 1.0f, 0.95f}));
    }
  }
  return out;
}

NoteBox draw_wall_name(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                       float height, std::string_view name) {
  if (scene.kind != SceneKind::wall || scene.targets.empty()) return {};
  const Target& wall = scene.targets.front();
  const glm::dvec2 under = render::project_to_screen(view_proj, {(wall.x_min + wall.x_max) / 2,
                                                                   wall.top_y - wall.thickness_m, 0.0});
  constexpr float kScale = 0.8f;
  const float em = overlay.atlas().pixel_height() * kScale;
  NoteBox box = band_for(overlay.atlas(), name, kScale);
  box.x = static_cast<float>(under.x) * width - box.width / 2;
  // A plaque on the wall's lower part, far from the top face where it is tapped, and above
  // the corner notes' row (draw_corner_note) at the screen's foot.
  box.y = std::min(static_cast<float>(under.y) * height - box.height - em * 0.5f, height - em * 3.2f);
  return draw_on_band(overlay, box, name, kScale, 0.55f, {1.0f, 1.0f, 1.0f, 0.95f});
}

void draw_note_names(render::Overlay& overlay, const Scene& scene, const glm::mat4& view_proj, float width,
                     float height) {
  if (scene.kind != SceneKind::percussion) return;
  std::vector<BarLabel> labels;
  for (const Target& t : scene.targets) labels.push_back({t.id, note_name(t.note)});
  draw_bar_labels(overlay, scene, view_proj, width, height, labels);
}

}  // namespace mallet::render
