#include "render/scene_view.hpp"

#include <random>

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
