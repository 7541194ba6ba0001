// The mallet head as a visitor sees it: a smooth ball with a smooth edge. Its pixels' coverage
// is read back from two frames that differ only in what lies behind it (the room cleared
// black, then white): where the head covers a share α of a pixel, the white frame is
// lighter by 1 − α (blending is in linear light).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "render/image.hpp"
#include "render/render_setup.hpp"
#include "render/scene_view.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

double linear(std::uint8_t v) { return srgb_to_linear(v / 255.0); }

std::unique_ptr<HeadlessRenderer> renderer(const Scene& scene, std::array<float, 3> clear, VkExtent2D size,
                                           VkSampleCountFlagBits samples) {
  HeadlessOptions o;
  o.size = size;
  o.settings.samples = samples;
  o.settings.clear_color = clear;
  o.validation = Validation::required;
  o.cache_dir = "";
  o.device = "llvmpipe";
  return std::make_unique<HeadlessRenderer>(scene, o);
}

struct Head {
  Image on_black, on_white;
  double cx = 0, cy = 0;  //!< its centre on the image, pixels
  double r = 0;           //!< its radius on the image, pixels (at the plane z = 0: a little less than its outline's)
  //! The square around it, 2.5 radii each way, that shows nothing else (the room behind it).
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double coverage(int x, int y) const {
    double lighter = 0;
    for (int c = 0; c < 3; ++c) lighter += linear(on_white.at(x, y)[c]) - linear(on_black.at(x, y)[c]);
    return std::clamp(1.0 - lighter / 3, 0.0, 1.0);
  }
};

//! The percussion scene's head high above the instruments, with nothing but the room behind it.
Head head_over_the_room(VkExtent2D size, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT) {
  const Scene& scene = test::percussion();
  FrameState s;
  s.mallet_centre = {-0.21, 0.22};
  Head h;
  auto black = renderer(scene, {0.0f, 0.0f, 0.0f}, size, samples);
  h.on_black = black->render(s);
  EXPECT_EQ(black->context().validation_messages(), 0u) << black->context().first_validation_message();
  h.on_white = renderer(scene, {1.0f, 1.0f, 1.0f}, size, samples)->render(s);
  const double aspect = static_cast<double>(size.width) / size.height;
  const glm::dvec2 c = project_to_screen(sphere_view_projection(scene, aspect, s.mallet_centre),
                                         {s.mallet_centre.x, s.mallet_centre.y, 0.0});
  const glm::dvec2 side = project_to_screen(sphere_view_projection(scene, aspect, s.mallet_centre),
                                            {s.mallet_centre.x + scene.mallet_radius_m, s.mallet_centre.y, 0.0});
  h.cx = c.x * size.width;
  h.cy = c.y * size.height;
  h.r = (side.x - c.x) * size.width;
  h.x0 = static_cast<int>(h.cx - 2.5 * h.r), h.x1 = static_cast<int>(h.cx + 2.5 * h.r);
  h.y0 = static_cast<int>(h.cy - 2.5 * h.r), h.y1 = static_cast<int>(h.cy + 2.5 * h.r);
  EXPECT_GE(h.x0, 0);
  EXPECT_GE(h.y0, 0);
  EXPECT_LT(h.x1, static_cast<int>(size.width));
  EXPECT_LT(h.y1, static_cast<int>(size.height));
  // Nothing but the room on the square's sides.
  for (int x = h.x0; x <= h.x1; ++x) EXPECT_EQ(h.coverage(x, h.y0) + h.coverage(x, h.y1), 0.0) << x;
  for (int y = h.y0; y <= h.y1; ++y) EXPECT_EQ(h.coverage(h.x0, y) + h.coverage(h.x1, y), 0.0) << y;
  return h;
}

TEST(MalletHead, ItsEdgeIsAntialiasedAllRoundAndItsAreaIsTheDisc) {
  for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT}) {
    const Head h = head_over_the_room({960, 540}, samples);
    // Its radius from its area, and the pixels its edge covers in part.
    double area = 0;
    int partial = 0, full = 0;
    std::vector<double> edge_angles;
    for (int y = h.y0; y <= h.y1; ++y)
      for (int x = h.x0; x <= h.x1; ++x) {
        const double a = h.coverage(x, y);
        area += a;
        if (a > 0.98) ++full;
        if (a > 0.05 && a < 0.95) {
          ++partial;
          edge_angles.push_back(std::atan2(y + 0.5 - h.cy, x + 0.5 - h.cx));
        }
      }
    const double r = std::sqrt(area / std::numbers::pi);
    ASSERT_GT(r, 8.0) << samples << " samples";
    ASSERT_GT(full, 0);
    // An aliased edge has none: every pixel is the head's or the room's. An antialiased one
    // has about one per pixel of its outline, on every side.
    EXPECT_GT(partial, 2 * std::numbers::pi * r * 0.6) << samples << " samples, radius " << r;
    std::vector<int> octants(8, 0);
    for (double angle : edge_angles)
      ++octants[static_cast<std::size_t>(std::clamp((angle + std::numbers::pi) / (std::numbers::pi / 4), 0.0, 7.0))];
    for (int o = 0; o < 8; ++o) EXPECT_GT(octants[o], r / 4) << "octant " << o << ", " << samples << " samples";
    // Round: every partly covered pixel lies on the circle of that radius about its centre,
    // within a pixel (no bumps where a polygon's corners were).
    EXPECT_NEAR(r, h.r, 0.05 * h.r);
    for (int y = h.y0; y <= h.y1; ++y)
      for (int x = h.x0; x <= h.x1; ++x) {
        const double a = h.coverage(x, y);
        if (a <= 0.05 || a >= 0.95) continue;
        const double d = std::hypot(x + 0.5 - h.cx, y + 0.5 - h.cy);
        EXPECT_NEAR(d, r, 1.0) << "(" << x << ", " << y << ") covered " << a;
      }
  }
}

TEST(MalletHead, ItsShadingHasNoBandAcrossIt) {
  // Down the vertical diameter, from the highlight to the dark underside, the light's slope
  // changes smoothly: no step in it from one pixel to the next (a terminator's hard corner,
  // a seam at the equator), however large the head is drawn.
  const Head h = head_over_the_room({1920, 1080});
  const int x = static_cast<int>(std::floor(h.cx));
  std::vector<double> light;
  for (int y = h.y0; y <= h.y1; ++y)
    if (h.coverage(x, y) > 0.999) {
      double l = 0;
      for (int c = 0; c < 3; ++c) l += linear(h.on_black.at(x, y)[c]) / 3;
      light.push_back(l);
    }
  ASSERT_GT(light.size(), 40u);
  // From the highlight (clipped at white on top) down: below the centre's row.
  const std::size_t from = light.size() / 2;
  double steepest = 0;
  for (std::size_t i = from + 1; i < light.size(); ++i) steepest = std::max(steepest, std::abs(light[i] - light[i - 1]));
  ASSERT_GT(steepest, 0.0);
  for (std::size_t i = from + 2; i < light.size() - 1; ++i) {
    const double bend = std::abs((light[i] - light[i - 1]) - (light[i - 1] - light[i - 2]));
    EXPECT_LT(bend, 0.35 * steepest) << "row " << i << " of " << light.size() << " down the head";
  }
}

}  // namespace
}  // namespace mallet::render
