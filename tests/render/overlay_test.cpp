// The overlay's geometry: rectangles, frames, discs, rings and progress arcs cover exactly
// their shapes (checked by area and by probing points), circles stay within a quarter pixel
// of the true circle, a progress ring starts at 12 o'clock and turns clockwise on a y-down
// screen, text is placed by its measured width; every index is in range.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "render/font_atlas.hpp"
#include "render/overlay.hpp"

namespace mallet::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::array<float, 4> kRed{1.0f, 0.0f, 0.0f, 1.0f};
constexpr std::array<float, 4> kTranslucentBlue{0.1f, 0.2f, 0.9f, 0.5f};

const FontAtlas& atlas() {
  static const FontAtlas baked(24.0f);
  return baked;
}

struct Point {
  double x, y;
};

Point at(const Overlay& o, std::uint32_t i) { return {o.vertices()[i].x, o.vertices()[i].y}; }

//! Twice the signed area; positive = clockwise as seen on a y-down screen.
double cross(Point a, Point b, Point c) { return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y); }

//! Checks the mesh is well formed (whole triangles, indices in range, all clockwise and not
//! degenerate) and returns its area.
double checked_area(const Overlay& o) {
  const auto& idx = o.indices();
  EXPECT_EQ(idx.size() % 3, 0u);
  double area = 0;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_LT(idx[t + k], o.vertices().size()) << "index " << t + k;
      if (idx[t + k] >= o.vertices().size()) return 0;
    }
    const double c = cross(at(o, idx[t]), at(o, idx[t + 1]), at(o, idx[t + 2]));
    EXPECT_GT(c, 0.0) << "triangle " << t / 3 << " is counter-clockwise or degenerate";
    area += c / 2;
  }
  return area;
}

//! How many triangles hold (x, y) strictly inside: 1 inside a shape, 0 outside it.
int cover(const Overlay& o, double x, double y) {
  const auto& idx = o.indices();
  const Point p{x, y};
  int n = 0;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const Point a = at(o, idx[t]), b = at(o, idx[t + 1]), c = at(o, idx[t + 2]);
    if (cross(a, b, p) > 0 && cross(b, c, p) > 0 && cross(c, a, p) > 0) ++n;
  }
  return n;
}

//! A point at `radius` from (cx, cy), `degrees` clockwise from 12 o'clock (y down).
Point clock(double cx, double cy, double radius, double degrees) {
  const double t = degrees * kPi / 180;
  return {cx + radius * std::sin(t), cy - radius * std::cos(t)};
}

void expect_solid(const Overlay& o, std::array<float, 4> color) {
  for (const OverlayVertex& v : o.vertices()) {
    EXPECT_EQ(v.u, atlas().solid_u());
    EXPECT_EQ(v.v, atlas().solid_v());
    EXPECT_EQ(v.color, color);
  }
}

TEST(OverlayRect, FillIsTwoTrianglesCoveringExactlyTheRect) {
  Overlay o(atlas());
  o.fill_rect(10, 20, 30, 15, kRed);
  ASSERT_EQ(o.vertices().size(), 4u);
  ASSERT_EQ(o.indices().size(), 6u);
  EXPECT_DOUBLE_EQ(checked_area(o), 30.0 * 15.0);
  for (const OverlayVertex& v : o.vertices()) {
    EXPECT_TRUE(v.x == 10 || v.x == 40) << v.x;
    EXPECT_TRUE(v.y == 20 || v.y == 35) << v.y;
  }
  // Probes off the diagonal: each point inside is covered once, none outside.
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 5; ++j) EXPECT_EQ(cover(o, 10 + 30 * (i + 0.37) / 7, 20 + 15 * (j + 0.37) / 5), 1);
  EXPECT_EQ(cover(o, 9.9, 27), 0);
  EXPECT_EQ(cover(o, 40.1, 27), 0);
  EXPECT_EQ(cover(o, 25, 19.9), 0);
  EXPECT_EQ(cover(o, 25, 35.1), 0);
  expect_solid(o, kRed);
}

TEST(OverlayRect, StrokeIsAFrameCentredOnTheOutline) {
  Overlay o(atlas());
  o.stroke_rect(10, 10, 100, 50, 4, kTranslucentBlue);
  EXPECT_NEAR(checked_area(o), 104.0 * 54.0 - 96.0 * 46.0, 1e-6);
  // Each side's band, from 2 px outside the outline to 2 px inside, covered once.
  EXPECT_EQ(cover(o, 60.3, 8.4), 1);
  EXPECT_EQ(cover(o, 60.3, 11.6), 1);
  EXPECT_EQ(cover(o, 111.7, 35.2), 1);
  EXPECT_EQ(cover(o, 60.3, 60.1), 1);
  EXPECT_EQ(cover(o, 8.3, 35.2), 1);
  EXPECT_EQ(cover(o, 60.3, 7.9), 0);   // beyond the outer edge
  EXPECT_EQ(cover(o, 60.3, 12.1), 0);  // inside the hole
  EXPECT_EQ(cover(o, 60.3, 35.2), 0);
  EXPECT_EQ(cover(o, 112.1, 35.2), 0);
  expect_solid(o, kTranslucentBlue);
}

TEST(OverlayRect, AStrokeWiderThanTheHoleFillsTheRect) {
  Overlay o(atlas());
  o.stroke_rect(0, 0, 4, 4, 10, kRed);
  EXPECT_EQ(o.vertices().size(), 4u);
  EXPECT_DOUBLE_EQ(checked_area(o), 14.0 * 14.0);
  EXPECT_EQ(cover(o, 2.1, 2.3), 1);
}

class OverlayCircle : public testing::TestWithParam<float> {};

TEST_P(OverlayCircle, StaysWithinAQuarterPixelAndKeepsTheArea) {
  const float r = GetParam();
  const double cx = 200.5, cy = 100.25;
  Overlay o(atlas());
  o.fill_circle(static_cast<float>(cx), static_cast<float>(cy), r, kRed);
  const double area = checked_area(o);
  EXPECT_NEAR(area, kPi * r * r, 0.005 * kPi * r * r);
  // The rim: its vertices and the middles of its chords (where a polygon strays most inward).
  const auto& idx = o.indices();
  for (std::size_t t = 0; t < idx.size(); t += 3) {
    const Point centre = at(o, idx[t]), a = at(o, idx[t + 1]), b = at(o, idx[t + 2]);
    EXPECT_NEAR(std::hypot(centre.x - cx, centre.y - cy), 0.0, 1e-4);
    EXPECT_NEAR(std::hypot(a.x - cx, a.y - cy), r, 0.25);
    EXPECT_NEAR(std::hypot((a.x + b.x) / 2 - cx, (a.y + b.y) / 2 - cy), r, 0.25);
  }
  for (int deg = 0; deg < 360; deg += 7) {  // probes off the vertices' angles (shared edges)
    const Point in = clock(cx, cy, r - 0.26, deg + 0.3183), out = clock(cx, cy, r + 0.26, deg + 0.3183);
    EXPECT_EQ(cover(o, in.x, in.y), 1) << deg;
    EXPECT_EQ(cover(o, out.x, out.y), 0) << deg;
  }
  expect_solid(o, kRed);
}

INSTANTIATE_TEST_SUITE_P(OverlayCircleRadii, OverlayCircle, testing::Values(1.5f, 6.0f, 40.0f, 250.0f, 1000.0f));

TEST(OverlayCircleSegments, GrowWithTheRadius) {
  std::size_t last = 0;
  for (const float r : {2.0f, 10.0f, 40.0f, 160.0f, 640.0f}) {
    Overlay o(atlas());
    o.fill_circle(0, 0, r, kRed);
    EXPECT_GE(o.vertices().size(), last) << r;
    last = o.vertices().size();
  }
  EXPECT_GT(last, 64u);
}

TEST(OverlayRing, StrokeCircleIsARingCentredOnTheCircle) {
  const double cx = 300, cy = 200, r = 50, w = 6;
  Overlay o(atlas());
  o.stroke_circle(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(r), static_cast<float>(w),
                  kTranslucentBlue);
  const double ro = r + w / 2, ri = r - w / 2;
  EXPECT_NEAR(checked_area(o), kPi * (ro * ro - ri * ri), 0.005 * kPi * (ro * ro - ri * ri));
  for (const OverlayVertex& v : o.vertices()) {
    const double d = std::hypot(v.x - cx, v.y - cy);
    EXPECT_TRUE(std::abs(d - ro) <= 0.25 || std::abs(d - ri) <= 0.25) << d;
  }
  for (int deg = 0; deg < 360; deg += 5) {
    const double off = deg + 0.2718;  // never on a vertex's angle (a shared edge)
    const Point on = clock(cx, cy, r, off), hole = clock(cx, cy, ri - 0.3, off), out = clock(cx, cy, ro + 0.3, off);
    EXPECT_EQ(cover(o, on.x, on.y), 1) << deg;
    EXPECT_EQ(cover(o, hole.x, hole.y), 0) << deg;
    EXPECT_EQ(cover(o, out.x, out.y), 0) << deg;
  }
  EXPECT_EQ(cover(o, cx + 0.1, cy + 0.2), 0);
  expect_solid(o, kTranslucentBlue);
}

TEST(OverlayRing, ALineWiderThanTheDiameterGivesADisc) {
  Overlay o(atlas());
  o.stroke_circle(0, 0, 3, 10, kRed);
  EXPECT_NEAR(checked_area(o), kPi * 64, 0.005 * kPi * 64);
  EXPECT_EQ(cover(o, 0.1, 0.2), 1);
}

//! Angle of a point clockwise from 12 o'clock around (cx, cy), in [−small, 2π).
double clock_angle(double cx, double cy, double x, double y) {
  const double t = std::atan2(x - cx, -(y - cy));
  return t < -1e-3 ? t + 2 * kPi : t;
}

TEST(OverlayProgress, AQuarterSpansTwelveToThreeOClock) {
  const double cx = 100, cy = 100, r = 40;
  Overlay o(atlas());
  o.progress_ring(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(r), 8, 0.25f, kRed);
  const double area = checked_area(o);
  double lo = 10, hi = -10;
  for (const OverlayVertex& v : o.vertices()) {
    const double t = clock_angle(cx, cy, v.x, v.y);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
    EXPECT_GE(v.x, cx - 1e-4);  // the right half...
    EXPECT_LE(v.y, cy + 1e-4);  // ...and the upper half (y down)
  }
  EXPECT_NEAR(lo, 0.0, 1e-5);
  EXPECT_NEAR(hi, kPi / 2, 1e-5);
  for (const double deg : {0.5, 20.3, 44.7, 70.3, 89.5})  // off the vertices' angles
    EXPECT_EQ(cover(o, clock(cx, cy, r, deg).x, clock(cx, cy, r, deg).y), 1) << deg;
  for (const double deg : {-0.5, 90.5, 135.0, 180.0, 270.0, 359.0})
    EXPECT_EQ(cover(o, clock(cx, cy, r, deg).x, clock(cx, cy, r, deg).y), 0) << deg;

  Overlay whole(atlas());
  whole.stroke_circle(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(r), 8, kRed);
  EXPECT_NEAR(area, checked_area(whole) / 4, 1e-3);
}

TEST(OverlayProgress, HalfEndsAtSixOClock) {
  Overlay o(atlas());
  o.progress_ring(0, 0, 30, 4, 0.5f, kRed);
  checked_area(o);
  double hi = -10;
  for (const OverlayVertex& v : o.vertices()) hi = std::max(hi, clock_angle(0, 0, v.x, v.y));
  EXPECT_NEAR(hi, kPi, 1e-5);
  EXPECT_EQ(cover(o, clock(0, 0, 30, 179).x, clock(0, 0, 30, 179).y), 1);
  EXPECT_EQ(cover(o, clock(0, 0, 30, 181).x, clock(0, 0, 30, 181).y), 0);
}

TEST(OverlayProgress, NothingDoneDrawsNothingAndMoreThanAllIsAll) {
  Overlay o(atlas());
  o.progress_ring(0, 0, 30, 4, 0.0f, kRed);
  o.progress_ring(0, 0, 30, 4, -0.3f, kRed);
  o.progress_ring(0, 0, 30, 4, std::numeric_limits<float>::quiet_NaN(), kRed);
  EXPECT_TRUE(o.vertices().empty());
  EXPECT_TRUE(o.indices().empty());

  Overlay over(atlas()), ring(atlas());
  over.progress_ring(0, 0, 30, 4, 1.7f, kRed);
  ring.stroke_circle(0, 0, 30, 4, kRed);
  EXPECT_EQ(over.vertices().size(), ring.vertices().size());
  EXPECT_EQ(over.indices(), ring.indices());
}

TEST(OverlayText, TheBaselineIsAtY) {
  Overlay o(atlas());
  o.text(50, 100, "A", kRed);
  ASSERT_EQ(o.vertices().size(), 4u);
  const GlyphQuad a = *atlas().quad(atlas().shape("A").glyphs.at(0));
  double top = 1e9, bottom = -1e9;
  for (const OverlayVertex& v : o.vertices()) {
    top = std::min(top, double{v.y});
    bottom = std::max(bottom, double{v.y});
  }
  EXPECT_NEAR(bottom, 100, 1.0);  // a capital stands on the baseline
  EXPECT_DOUBLE_EQ(top, 100 + a.y0);
  EXPECT_FLOAT_EQ(o.vertices()[0].x, 50 + a.x0);
  EXPECT_EQ(o.vertices()[0].u, a.u0);
  EXPECT_EQ(o.vertices()[2].v, a.v1);
}

TEST(OverlayText, AlignmentPlacesTheMeasuredWidth) {
  const char* label = "Glockenspiel \xC3\xA9t\xC3\xA9 AV";
  const float width = atlas().measure(label);
  Overlay left(atlas()), centre(atlas()), right(atlas());
  EXPECT_FLOAT_EQ(left.text(0, 300, label, kRed), width);
  EXPECT_FLOAT_EQ(centre.text(400, 300, label, kRed, TextAlign::center), width);
  EXPECT_FLOAT_EQ(right.text(400, 300, label, kRed, TextAlign::right), width);
  ASSERT_EQ(centre.vertices().size(), left.vertices().size());
  ASSERT_EQ(right.vertices().size(), left.vertices().size());
  for (std::size_t i = 0; i < left.vertices().size(); ++i) {
    // Each glyph on a whole pixel (both ways set): within a pixel of the one set at the left.
    EXPECT_NEAR(centre.vertices()[i].x, left.vertices()[i].x + 400 - width / 2, 1.0);
    EXPECT_NEAR(right.vertices()[i].x, left.vertices()[i].x + 400 - width, 1.0);
    EXPECT_EQ(centre.vertices()[i].y, left.vertices()[i].y);
    EXPECT_EQ(centre.vertices()[i].u, left.vertices()[i].u);
  }
  EXPECT_EQ(centre.indices(), left.indices());
  // The ink of centred text sits around x, within a glyph's side bearing of ±width/2.
  float lo = 1e9f, hi = -1e9f;
  for (const OverlayVertex& v : centre.vertices()) {
    lo = std::min(lo, v.x);
    hi = std::max(hi, v.x);
  }
  EXPECT_NEAR(lo, 400 - width / 2, 3.0);
  EXPECT_NEAR(hi, 400 + width / 2, 3.0);
  EXPECT_NEAR((lo + hi) / 2, 400, 1.5);
  checked_area(centre);
}

TEST(OverlayText, SpacesAdvanceWithoutQuadsAndColoursAreCopied) {
  Overlay o(atlas());
  const float width = o.text(0, 50, "A A", kTranslucentBlue);
  EXPECT_EQ(o.vertices().size(), 8u);
  EXPECT_EQ(o.indices().size(), 12u);
  EXPECT_FLOAT_EQ(width, atlas().measure("A A"));
  const ShapedText& set = atlas().shape("A A");
  ASSERT_EQ(set.glyphs.size(), 3u);
  EXPECT_NEAR(o.vertices()[4].x - o.vertices()[0].x, set.glyphs[2].x - set.glyphs[0].x, 1.0);  // whole pixels
  EXPECT_GT(set.glyphs[2].x - set.glyphs[1].x, 0.0f);  // the space advances
  for (const OverlayVertex& v : o.vertices()) EXPECT_EQ(v.color, kTranslucentBlue);
}

TEST(OverlayText, BrokenUtf8DrawsReplacementCharacters) {
  Overlay broken(atlas()), question(atlas());
  EXPECT_FLOAT_EQ(broken.text(10, 40, "a\xFF" "b", kRed), question.text(10, 40, "a\uFFFD" "b", kRed));
  ASSERT_EQ(broken.vertices().size(), question.vertices().size());
  for (std::size_t i = 0; i < broken.vertices().size(); ++i) {
    EXPECT_EQ(broken.vertices()[i].x, question.vertices()[i].x);
    EXPECT_EQ(broken.vertices()[i].u, question.vertices()[i].u);
  }
}

TEST(Overlay, ShapesAccumulateWithIndicesInRangeAndClearEmpties) {
  Overlay o(atlas());
  o.fill_rect(0, 0, 10, 10, kRed);
  o.stroke_rect(5, 5, 20, 20, 2, kTranslucentBlue);
  o.fill_circle(50, 50, 12, kRed);
  o.stroke_circle(50, 50, 20, 3, kTranslucentBlue);
  o.progress_ring(80, 80, 15, 4, 0.6f, kRed);
  o.text(10, 90, "Xylophone", kTranslucentBlue, TextAlign::right);
  EXPECT_GT(o.indices().size(), 100u);
  EXPECT_GT(checked_area(o), 0.0);
  EXPECT_EQ(&o.atlas(), &atlas());
  o.clear();
  EXPECT_TRUE(o.vertices().empty());
  EXPECT_TRUE(o.indices().empty());
}

TEST(Overlay, DegenerateSizesDrawNothing) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Overlay o(atlas());
  o.fill_rect(0, 0, 0, 10, kRed);
  o.fill_rect(0, 0, -5, 10, kRed);
  o.fill_rect(nan, 0, 5, 10, kRed);
  o.fill_rect(0, 0, inf, 10, kRed);
  o.stroke_rect(0, 0, 10, 10, 0, kRed);
  o.fill_circle(0, 0, 0, kRed);
  o.fill_circle(0, 0, nan, kRed);
  o.stroke_circle(0, 0, 10, -1, kRed);
  o.progress_ring(0, 0, inf, 2, 0.5f, kRed);
  EXPECT_FLOAT_EQ(o.text(nan, 0, "A", kRed), atlas().measure("A"));
  EXPECT_TRUE(o.vertices().empty());
  EXPECT_TRUE(o.indices().empty());
}

}  // namespace
}  // namespace mallet::render
