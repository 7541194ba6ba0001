#include "render/scene_view.hpp"

#include <cmath>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace mallet::render {
namespace {

using test::percussion;

TEST(SceneView, ThePlaneOfTheMalletMapsOntoTheScreenExactlyAsThePointerDoes) {
  const Scene& s = percussion();
  const glm::mat4 vp = view_projection(s);
  for (double sx : {0.0, 0.13, 0.5, 0.92, 1.0})
    for (double sy : {0.0, 0.4, 0.77, 1.0}) {
      const Vec2 w = s.screen_to_world.map(sx, sy);
      const glm::dvec2 p = project_to_screen(vp, {w.x, w.y, 0.0});
      EXPECT_NEAR(p.x, sx, 1e-5) << sx << "," << sy;
      EXPECT_NEAR(p.y, sy, 1e-5) << sx << "," << sy;
    }
}

TEST(SceneView, OnEveryScreenShapeAMetreIsAsManyPixelsAcrossAsUpAndTheContentIsWhole) {
  // 16:9, 16:10, 4:3, 5:4, 21:9 and portrait 9:16, as images of those sizes.
  const Scene& s = percussion();
  for (const auto& [w, h] : {std::pair{1920, 1080}, {1920, 1200}, {1024, 768}, {1280, 1024}, {2560, 1080},
                             {1080, 1920}}) {
    const double aspect = static_cast<double>(w) / h;
    const glm::mat4 vp = view_projection(s, aspect);
    const ScreenToWorld framing = framed(s.screen_to_world, aspect);
    // The plane of the mallet maps onto the image as the pointer's framing says...
    for (double sx : {0.0, 0.3, 1.0})
      for (double sy : {0.0, 0.6, 1.0}) {
        const Vec2 world = framing.map(sx, sy);
        const glm::dvec2 p = project_to_screen(vp, {world.x, world.y, 0.0});
        EXPECT_NEAR(p.x, sx, 1e-5) << w << "x" << h;
        EXPECT_NEAR(p.y, sy, 1e-5) << w << "x" << h;
      }
    // ...unstretched: 10 cm across and 10 cm up cover the same pixels...
    const glm::dvec2 o = project_to_screen(vp, {0.0, 0.1, 0.0});
    const glm::dvec2 x = project_to_screen(vp, {0.1, 0.1, 0.0});
    const glm::dvec2 y = project_to_screen(vp, {0.0, 0.2, 0.0});
    EXPECT_NEAR((x.x - o.x) * w, (o.y - y.y) * h, 1e-3) << w << "x" << h;
    // ...and every bar is whole on the plane of the mallet.
    for (const Target& t : s.targets) {
      const glm::dvec2 a = project_to_screen(vp, {t.x_min, t.top_y, 0.0});
      const glm::dvec2 b = project_to_screen(vp, {t.x_max, t.top_y, 0.0});
      EXPECT_GE(a.x, 0.0) << w << "x" << h;
      EXPECT_LE(b.x, 1.0) << w << "x" << h;
      EXPECT_GT(a.y, 0.0) << w << "x" << h;
      EXPECT_LT(a.y, 1.0) << w << "x" << h;
    }
  }
}

//! The sphere's outline on a w × h image: its width and height in pixels.
glm::dvec2 outline_px(const glm::mat4& vp, glm::dvec3 centre, double radius, int w, int h) {
  glm::dvec2 lo{1e300}, hi{-1e300};
  for (int i = 0; i <= 90; ++i)
    for (int j = 0; j < 180; ++j) {
      const double theta = M_PI * i / 90, phi = 2 * M_PI * j / 180;
      const glm::dvec3 p = centre + radius * glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                        std::sin(theta) * std::sin(phi));
      const glm::dvec2 s = project_to_screen(vp, p) * glm::dvec2(w, h);
      lo = glm::min(lo, s);
      hi = glm::max(hi, s);
    }
  return hi - lo;
}

TEST(SceneView, TheMalletIsDrawnRoundAnywhereOnAnyScreenWhereTheOffAxisViewWouldStretchIt) {
  const Scene& s = percussion();
  const double r = s.mallet_radius_m;
  for (const auto& [w, h] : {std::pair{1920, 1080}, {1280, 1024}, {1080, 1920}}) {
    const double aspect = static_cast<double>(w) / h;
    const ScreenToWorld f = framed(s.screen_to_world, aspect);
    for (const Vec2 at : {f.map(0.03, 0.97), f.map(0.5, 0.5), f.map(0.97, 0.03), f.map(0.9, 0.8)}) {
      const glm::dvec2 round = outline_px(sphere_view_projection(s, aspect, at), {at.x, at.y, 0.0}, r, w, h);
      EXPECT_NEAR(round.y / round.x, 1.0, 2e-3) << w << "x" << h << " at " << at.x << "," << at.y;
      // Where the plane of the mallet is, the two views agree: the sphere stays put.
      const glm::dvec2 c0 = project_to_screen(view_projection(s, aspect), {at.x, at.y, 0.0});
      const glm::dvec2 c1 = project_to_screen(sphere_view_projection(s, aspect, at), {at.x, at.y, 0.0});
      EXPECT_NEAR(c0.x, c1.x, 1e-6);
      EXPECT_NEAR(c0.y, c1.y, 1e-6);
    }
  }
  // The eye's own view, from above, stretches it at the bottom of a 16:9 screen.
  const Vec2 low = s.screen_to_world.map(0.03, 0.97);
  const glm::dvec2 egg = outline_px(view_projection(s), {low.x, low.y, 0.0}, r, 1920, 1080);
  EXPECT_GT(egg.y / egg.x, 1.1);
}

TEST(SceneView, BarsAreSeenFromAboveInPerspective) {
  const Scene& s = percussion();
  const glm::mat4 vp = view_projection(s);
  const Target& bar = s.targets.at(0);
  // The bar's far end (z < 0) appears higher on screen than its near end, and nearer
  // things look bigger: the near end's width on screen exceeds the far end's.
  const glm::dvec2 near_l = project_to_screen(vp, {bar.x_min, bar.top_y, bar.length_m / 2});
  const glm::dvec2 near_r = project_to_screen(vp, {bar.x_max, bar.top_y, bar.length_m / 2});
  const glm::dvec2 far_l = project_to_screen(vp, {bar.x_min, bar.top_y, -bar.length_m / 2});
  const glm::dvec2 far_r = project_to_screen(vp, {bar.x_max, bar.top_y, -bar.length_m / 2});
  EXPECT_LT(far_l.y, near_l.y);
  EXPECT_GT(near_r.x - near_l.x, far_r.x - far_l.x);
}

TEST(SceneView, EveryBarIsPlacedAndScaledFromTheSceneAndRailsSitAtTheNodalPoints) {
  const Scene& s = percussion();
  const std::vector<Instance> all = instrument_instances(s);
  int bars = 0, rails = 0;
  for (const Instance& i : all) {
    if (i.target >= 0) {
      ++bars;
      const Target& t = s.targets.at(i.target);
      // The unit bar's top-right-near corner (0.5, 0, 0.5) lands on the bar's.
      const glm::vec4 c = i.transform * glm::vec4(0.5f, 0.0f, 0.5f, 1.0f);
      EXPECT_NEAR(c.x, t.x_max, 1e-6);
      EXPECT_NEAR(c.y, t.top_y, 1e-6);
      EXPECT_NEAR(c.z, t.length_m / 2, 1e-6);
      const glm::vec4 bottom = i.transform * glm::vec4(0.0f, -1.0f, 0.0f, 1.0f);
      EXPECT_NEAR(bottom.y, t.top_y - t.thickness_m, 1e-6);
    } else {
      ++rails;
      // The rail's top line starts under the first bar's nodal line.
      const glm::vec4 start = i.transform * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
      const Instrument& inst = start.x < 0 ? s.instruments.at(0) : s.instruments.at(1);
      const Target& first = s.targets.at(inst.targets.front());
      EXPECT_NEAR(std::abs(start.z), (0.5 - kNodalPoint) * first.length_m, 1e-6);
      EXPECT_NEAR(start.y, first.top_y - first.thickness_m, 1e-6);
    }
  }
  EXPECT_EQ(bars, static_cast<int>(s.targets.size()));
  EXPECT_EQ(rails, 2 * static_cast<int>(s.instruments.size()));
}

TEST(SceneView, TheMalletHeadIsTheScenesSphere) {
  const Scene& s = percussion();
  const Instance m = mallet_instance(s, {0.1, 0.2});
  const glm::vec4 top = m.transform * glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
  EXPECT_NEAR(top.x, 0.1, 1e-6);
  EXPECT_NEAR(top.y, 0.2 + s.mallet_radius_m, 1e-6);
}

TEST(SceneView, EveryPointTheSphereShadowsProjectsInsideItsShadowBounds) {
  // Points filling the instruments' box (in it, not only on the bars' surfaces, so the
  // check is stronger than the frames need); wherever the sphere darkens one, it must
  // project inside the rectangle the renderer redraws, and that rectangle must be a
  // small part of the image when the mallet is near the bars.
  const Scene& s = percussion();
  const glm::mat4 vp = view_projection(s);
  Box box;
  box.add({s.screen_to_world.left_m, -0.07, -0.2});
  box.add({s.screen_to_world.right_m, 0.0, 0.2});
  const int w = 1920, h = 1080;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int shadowed = 0;
  for (const Target& bar : s.targets)
    for (double above : {s.mallet_radius_m, 0.03, 0.25}) {
      SphereShadow sh{{bar.x_max, bar.top_y + above, 0.0}, s.mallet_radius_m,
                      glm::normalize(glm::dvec3(0.0, 1.0, 0.22)), 0.035};
      const PixelRect r = shadow_bounds(vp, w, h, sh, box);
      ASSERT_FALSE(r.empty());
      EXPECT_GE(r.x0, 0);
      EXPECT_LE(r.x1, w);
      EXPECT_GE(r.y0, 0);
      EXPECT_LE(r.y1, h);
      if (above < 0.05) {
        EXPECT_LT(double(r.x1 - r.x0) * (r.y1 - r.y0), 0.05 * w * h) << bar.id;
      }
      for (int i = 0; i < 4000; ++i) {
        // Near the axis of the shadow, where the shadowed points are, and anywhere in the box.
        glm::dvec3 p = i % 2 ? glm::dvec3(sh.centre.x + (u(rng) - 0.5) * 0.2, box.lo.y + u(rng) * 0.07,
                                          sh.centre.z - 0.05 + (u(rng) - 0.5) * 0.2)
                             : box.lo + (box.hi - box.lo) * glm::dvec3(u(rng), u(rng), u(rng));
        p = glm::clamp(p, box.lo, box.hi);
        if (sphere_visibility(sh, p) >= 1.0) continue;
        ++shadowed;
        const glm::dvec2 q = project_to_screen(vp, p) * glm::dvec2(w, h);
        EXPECT_TRUE(q.x >= r.x0 && q.x <= r.x1 && q.y >= r.y0 && q.y <= r.y1)
            << "bar " << bar.id << " +" << above << ": (" << q.x << ", " << q.y << ") outside [" << r.x0 << ", "
            << r.x1 << ") x [" << r.y0 << ", " << r.y1 << ")";
      }
    }
  EXPECT_GT(shadowed, 1000);  // the check saw many shadowed points
}

TEST(SceneView, ASphereThatShadowsNothingInTheBoxHasNoShadowBounds) {
  const Scene& s = percussion();
  Box box;
  box.add({-0.3, -0.07, -0.2});
  box.add({0.3, 0.0, 0.2});
  const glm::dvec3 up = glm::normalize(glm::dvec3(0.0, 1.0, 0.22));
  // Below the box, lit from above: its shadow falls away from it.
  EXPECT_TRUE(shadow_bounds(view_projection(s), 640, 360, {{0.0, -0.5, 0.0}, 0.01, up, 0.035}, box).empty());
  // Far to the side: the shadow's cone misses the box.
  EXPECT_TRUE(shadow_bounds(view_projection(s), 640, 360, {{2.0, 0.05, 0.0}, 0.01, up, 0.035}, box).empty());
  // No radius, no shadow.
  EXPECT_TRUE(shadow_bounds(view_projection(s), 640, 360, {{0.0, 0.05, 0.0}, 0.0, up, 0.035}, box).empty());
}

}  // namespace
}  // namespace mallet::render
