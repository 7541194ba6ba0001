#pragma once
// The 2D overlay drawn over the scene (calibration targets, progress rings, hints,
// the operator page): a list of coloured triangles in pixel coordinates that all
// sample one single-channel atlas. Glyphs sample their coverage there; shapes sample a
// fully-covered texel, so one pipeline with straight alpha blending draws everything.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "render/font_atlas.hpp"

namespace mallet::render {

struct OverlayVertex {
  float x = 0, y = 0;             //!< pixels, origin top-left, y down
  float u = 0, v = 0;             //!< atlas coordinates (0..1)
  std::array<float, 4> color{};   //!< sRGB RGB, straight alpha
};

enum class TextAlign { left, center, right };

//! Where a text's ink landed: the box around its glyphs' quads, in pixels (x0, y0 top-left).
//! Every text drawn leaves one, so that what a screen shows can be checked for words drawn
//! over words or off the screen (the overlap contract: tests/app/kiosk/text_boxes_test.cpp).
struct TextBox {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  std::string text;
};
inline bool overlap(const TextBox& a, const TextBox& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

//! Triangles wind clockwise on screen; no shape overlaps itself (a translucent shape blends
//! once); circles stray < 0.25 px from the true circle and keep its area; degenerate or
//! non-finite sizes draw nothing.
class Overlay {
 public:
  explicit Overlay(const FontAtlas& atlas) : atlas_(&atlas) {}

  void clear();
  void fill_rect(float x, float y, float w, float h, std::array<float, 4> color);
  void stroke_rect(float x, float y, float w, float h, float line_width, std::array<float, 4> color);
  void fill_circle(float cx, float cy, float radius, std::array<float, 4> color);
  void stroke_circle(float cx, float cy, float radius, float line_width, std::array<float, 4> color);
  //! A ring from 12 o'clock clockwise over `fraction` (0..1) of the turn: a progress ring.
  void progress_ring(float cx, float cy, float radius, float line_width, float fraction,
                     std::array<float, 4> color);
  //! UTF-8 text with its baseline at y; returns the advance width in pixels. `scale` sets
  //! it smaller than the atlas's size (the operator page's dense text; 0.5..1: the atlas's
  //! linear filter shrinks a glyph cleanly down to half).
  float text(float x, float y, std::string_view utf8, std::array<float, 4> color,
             TextAlign align = TextAlign::left, float scale = 1.0f);

  const std::vector<OverlayVertex>& vertices() const { return vertices_; }
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  //! Each text drawn since clear(), in order (a text with no ink, all spaces, leaves none).
  const std::vector<TextBox>& text_boxes() const { return text_boxes_; }
  const FontAtlas& atlas() const { return *atlas_; }

 private:
  std::uint32_t solid_vertex(float x, float y, const std::array<float, 4>& color);
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d);
  //! From 12 o'clock clockwise over `fraction` (0..1] of a turn, between two radii (a fan
  //! from the centre when `inner` ≤ 0).
  void arc(float cx, float cy, float inner, float outer, float fraction, std::array<float, 4> color);

  const FontAtlas* atlas_;
  std::vector<OverlayVertex> vertices_;
  std::vector<std::uint32_t> indices_;
  std::vector<TextBox> text_boxes_;
};

}  // namespace mallet::render
