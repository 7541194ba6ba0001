#include "render/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

// Conventions of the geometry built here:
// * triangles wind clockwise on screen (y down); the overlay pipeline need not cull;
// * no two triangles of one shape overlap, so a translucent shape blends exactly once;
// * degenerate or non-finite sizes (w ≤ 0, radius ≤ 0, NaN, ...) draw nothing rather than
//   throwing: layout arithmetic on odd screens must not end the kiosk.
namespace mallet::render {
namespace {

constexpr float kTurn = 2.0f * std::numbers::pi_v<float>;
constexpr float kMaxChordError = 0.25f;  // px: below what a viewer can tell from a true circle
constexpr int kMinSegments = 8;
constexpr int kMaxSegments = 4096;

bool positive(float v) { return std::isfinite(v) && v > 0.0f; }

//! Segments of a whole turn at `radius` so that the polygon strays less than kMaxChordError
//! from the circle: the sagitta r·(1 − cos(π/n)) ≤ e gives n ≥ π / acos(1 − e/r). A multiple
//! of 4 so that 12, 3, 6 and 9 o'clock are vertices (progress quarters end exactly there).
int segments_for(float radius) {
  const double c = 1.0 - double{kMaxChordError} / double{radius};
  const double n = c <= -1.0 ? 1.0 : std::ceil(std::numbers::pi / std::acos(c));
  const int whole = static_cast<int>(std::clamp(n, double{kMinSegments}, double{kMaxSegments}));
  return (whole + 3) / 4 * 4;
}

//! Vertices go slightly outside the circle so that the n-gon has the circle's area,
//! πr² = k²r²·(n/2)·sin(2π/n): a filled disc or ring then carries the same ink as the true
//! shape (it reads the same size), and the outline still strays less than one sagitta.
float area_scale(int segments) {
  const double n = segments;
  return static_cast<float>(std::sqrt(2.0 * std::numbers::pi / (n * std::sin(2.0 * std::numbers::pi / n))));
}

}  // namespace

void Overlay::clear() {
  vertices_.clear();
  indices_.clear();
  text_boxes_.clear();
}

std::uint32_t Overlay::solid_vertex(float x, float y, const std::array<float, 4>& color) {
  vertices_.push_back({x, y, atlas_->solid_u(), atlas_->solid_v(), color});
  return static_cast<std::uint32_t>(vertices_.size() - 1);
}

void Overlay::triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  indices_.insert(indices_.end(), {a, b, c});
}

void Overlay::quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  triangle(a, b, c);
  triangle(a, c, d);
}

void Overlay::fill_rect(float x, float y, float w, float h, std::array<float, 4> color) {
  if (!std::isfinite(x) || !std::isfinite(y) || !positive(w) || !positive(h)) return;
  const auto a = solid_vertex(x, y, color);
  const auto b = solid_vertex(x + w, y, color);
  const auto c = solid_vertex(x + w, y + h, color);
  const auto d = solid_vertex(x, y + h, color);
  quad(a, b, c, d);
}

void Overlay::stroke_rect(float x, float y, float w, float h, float line_width, std::array<float, 4> color) {
  if (!std::isfinite(x) || !std::isfinite(y) || !positive(w) || !positive(h) || !positive(line_width)) return;
  const float half = line_width / 2;
  const float ox0 = x - half, oy0 = y - half, ox1 = x + w + half, oy1 = y + h + half;
  const float ix0 = x + half, iy0 = y + half, ix1 = x + w - half, iy1 = y + h - half;
  if (ix1 <= ix0 || iy1 <= iy0) {  // the line is wider than the hole: a filled rectangle
    fill_rect(ox0, oy0, ox1 - ox0, oy1 - oy0, color);
    return;
  }
  // A frame of four trapezoids between the outer and the inner rectangle (no overlap).
  const auto otl = solid_vertex(ox0, oy0, color), otr = solid_vertex(ox1, oy0, color);
  const auto obr = solid_vertex(ox1, oy1, color), obl = solid_vertex(ox0, oy1, color);
  const auto itl = solid_vertex(ix0, iy0, color), itr = solid_vertex(ix1, iy0, color);
  const auto ibr = solid_vertex(ix1, iy1, color), ibl = solid_vertex(ix0, iy1, color);
  quad(otl, otr, itr, itl);
  quad(otr, obr, ibr, itr);
  quad(obr, obl, ibl, ibr);
  quad(obl, otl, itl, ibl);
}

void Overlay::arc(float cx, float cy, float inner, float outer, float fraction, std::array<float, 4> color) {
  const int whole = segments_for(outer);
  const int segments = std::max(1, static_cast<int>(std::ceil(static_cast<float>(whole) * fraction)));
  const bool closed = fraction >= 1.0f;
  const float k = area_scale(whole);
  // Angle θ from 12 o'clock, clockwise on screen: with y down that is (sin θ, −cos θ).
  const auto rim = [&](float radius, int i) {
    const float theta = kTurn * fraction * static_cast<float>(i) / static_cast<float>(segments);
    return solid_vertex(cx + k * radius * std::sin(theta), cy - k * radius * std::cos(theta), color);
  };
  const int points = closed ? segments : segments + 1;  // a whole turn reuses its first point
  const auto first = static_cast<std::uint32_t>(vertices_.size());
  if (inner <= 0.0f) {
    // A fan from the centre: a disc, or a pie when the ring's hole closes.
    const auto centre = solid_vertex(cx, cy, color);
    for (int i = 0; i < points; ++i) rim(outer, i);
    const auto at = [&](int i) { return first + 1 + static_cast<std::uint32_t>(i % points); };
    for (int i = 0; i < segments; ++i) triangle(centre, at(i), at(i + 1));
    return;
  }
  for (int i = 0; i < points; ++i) {  // interleaved: outer i at 2i, inner i at 2i + 1
    rim(outer, i);
    rim(inner, i);
  }
  const auto outer_at = [&](int i) { return first + 2 * static_cast<std::uint32_t>(i % points); };
  for (int i = 0; i < segments; ++i) quad(outer_at(i), outer_at(i + 1), outer_at(i + 1) + 1, outer_at(i) + 1);
}

void Overlay::fill_circle(float cx, float cy, float radius, std::array<float, 4> color) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !positive(radius)) return;
  arc(cx, cy, 0.0f, radius, 1.0f, color);
}

void Overlay::stroke_circle(float cx, float cy, float radius, float line_width, std::array<float, 4> color) {
  progress_ring(cx, cy, radius, line_width, 1.0f, color);
}

void Overlay::progress_ring(float cx, float cy, float radius, float line_width, float fraction,
                            std::array<float, 4> color) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !positive(radius) || !positive(line_width)) return;
  if (!(fraction > 0.0f)) return;  // 0, negative and NaN: nothing done yet, nothing drawn
  const float outer = radius + line_width / 2;
  if (!std::isfinite(outer)) return;
  arc(cx, cy, radius - line_width / 2, outer, std::min(fraction, 1.0f), color);
}

float Overlay::text(float x, float y, std::string_view utf8, std::array<float, 4> color, TextAlign align,
                    float scale) {
  const ShapedText& shaped = atlas_->shape(utf8);
  const float width = shaped.width * scale;
  if (!std::isfinite(x) || !std::isfinite(y) || !(scale > 0)) return width;
  float pen = x;
  if (align == TextAlign::center) pen -= width / 2;
  if (align == TextAlign::right) pen -= width;
  TextBox ink{INFINITY, INFINITY, -INFINITY, -INFINITY, std::string(utf8)};
  for (const PlacedGlyph& g : shaped.glyphs) {
    const std::optional<GlyphQuad> q = atlas_->quad(g);
    if (!q) continue;  // a space has no quad, only an advance
    float gx = pen + g.x * scale, gy = y + g.y * scale;
    if (scale == 1.0f) {  // glyphs drawn at their size land on whole pixels: crisp
      gx = std::round(gx);
      gy = std::round(gy);
    }
    const auto first = static_cast<std::uint32_t>(vertices_.size());
    const float x0 = gx + q->x0 * scale, x1 = gx + q->x1 * scale, y0 = gy + q->y0 * scale, y1 = gy + q->y1 * scale;
    vertices_.push_back({x0, y0, q->u0, q->v0, color});
    vertices_.push_back({x1, y0, q->u1, q->v0, color});
    vertices_.push_back({x1, y1, q->u1, q->v1, color});
    vertices_.push_back({x0, y1, q->u0, q->v1, color});
    quad(first, first + 1, first + 2, first + 3);
    ink.x0 = std::min(ink.x0, x0);
    ink.y0 = std::min(ink.y0, y0);
    ink.x1 = std::max(ink.x1, x1);
    ink.y1 = std::max(ink.y1, y1);
  }
  if (ink.x1 > ink.x0) text_boxes_.push_back(std::move(ink));
  return width;
}

}  // namespace mallet::render
