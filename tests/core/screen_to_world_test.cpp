// The scene framed for a screen's proportions: unstretched, all of the content in view.
#include "core/screen_to_world.hpp"

#include <limits>

#include <gtest/gtest.h>

#include "core/view_aspect.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

// The museum screens the kiosk is put on: 16:9, 16:10, 4:3, 5:4, 21:9 and portrait 9:16.
constexpr double kAspects[] = {16.0 / 9, 16.0 / 10, 4.0 / 3, 5.0 / 4, 21.0 / 9, 9.0 / 16};

TEST(Framing, EveryScreenShowsAllOfTheContentUnstretchedAroundItsCentre) {
  const ScreenToWorld content = test::percussion().screen_to_world;
  for (double aspect : kAspects) {
    const ScreenToWorld f = framed(content, aspect);
    // A metre is as many pixels across as up: the rectangle has the screen's proportions.
    EXPECT_NEAR(f.width_m() / f.height_m(), aspect, 1e-12) << aspect;
    // All of the content is in view, and exactly one direction grew.
    EXPECT_LE(f.left_m, content.left_m);
    EXPECT_GE(f.right_m, content.right_m);
    EXPECT_GE(f.top_m, content.top_m);
    EXPECT_LE(f.bottom_m, content.bottom_m);
    const bool wider = f.width_m() > content.width_m() + 1e-12, taller = f.height_m() > content.height_m() + 1e-12;
    EXPECT_FALSE(wider && taller) << aspect;
    // The content stays in the middle.
    EXPECT_NEAR(f.left_m + f.right_m, content.left_m + content.right_m, 1e-12);
    EXPECT_NEAR(f.top_m + f.bottom_m, content.top_m + content.bottom_m, 1e-12);
  }
}

TEST(Framing, APointerAtTheScreensEdgeReachesTheOutermostBarsOnEveryScreen) {
  const Scene& scene = test::percussion();
  const Target& leftmost = scene.targets.front();
  const Target& rightmost = scene.targets.back();
  for (double aspect : kAspects) {
    const ScreenToWorld f = framed(scene.screen_to_world, aspect);
    EXPECT_LE(f.map(0.0, 0.5).x, leftmost.x_min) << aspect;
    EXPECT_GE(f.map(1.0, 0.5).x, rightmost.x_max) << aspect;
    // And reaches above and below every bar's top, to strike it from above.
    for (const Target& t : scene.targets) {
      EXPECT_GT(f.map(0.5, 0.0).y, t.top_y + scene.mallet_radius_m) << aspect;
      EXPECT_LT(f.map(0.5, 1.0).y, t.top_y) << aspect;
    }
  }
}

TEST(Framing, TheContentsOwnProportionsAndNonsenseLeaveItExactlyAsItIs) {
  const ScreenToWorld content = test::percussion().screen_to_world;  // 0.832 m × 0.468 m: 16:9
  for (double aspect : {1920.0 / 1080, 0.0, -1.0, std::numeric_limits<double>::infinity(),
                        std::numeric_limits<double>::quiet_NaN()}) {
    const ScreenToWorld f = framed(content, aspect);
    EXPECT_EQ(f.left_m, content.left_m) << aspect;
    EXPECT_EQ(f.right_m, content.right_m) << aspect;
    EXPECT_EQ(f.top_m, content.top_m) << aspect;
    EXPECT_EQ(f.bottom_m, content.bottom_m) << aspect;
  }
}

TEST(Framing, PortraitGrowsUpAndDownAndUltraWideGrowsLeftAndRight) {
  const ScreenToWorld content{-0.4, 0.4, 0.3, -0.15};  // 0.8 × 0.45
  const ScreenToWorld portrait = framed(content, 9.0 / 16);
  EXPECT_DOUBLE_EQ(portrait.left_m, -0.4);
  EXPECT_DOUBLE_EQ(portrait.right_m, 0.4);
  EXPECT_NEAR(portrait.height_m(), 0.8 * 16 / 9, 1e-12);
  const ScreenToWorld wide = framed(content, 21.0 / 9);
  EXPECT_DOUBLE_EQ(wide.top_m, 0.3);
  EXPECT_DOUBLE_EQ(wide.bottom_m, -0.15);
  EXPECT_NEAR(wide.width_m(), 0.45 * 21 / 9, 1e-12);
}

TEST(ViewAspect, AWindowsSizeSetsItAndAMinimisedWindowKeepsTheLastOne) {
  ViewAspect a;
  const ScreenToWorld content{-0.4, 0.4, 0.3, -0.15};
  EXPECT_EQ(framed(content, &a).left_m, content.left_m);  // not known yet: the content's own
  a.set(1280, 1024);
  EXPECT_DOUBLE_EQ(a.get(), 1.25);
  a.set(0, 0);  // minimised
  EXPECT_DOUBLE_EQ(a.get(), 1.25);
  EXPECT_NEAR(framed(content, &a).height_m(), 0.8 / 1.25, 1e-12);
  EXPECT_EQ(framed(content, static_cast<const ViewAspect*>(nullptr)).top_m, content.top_m);
}

}  // namespace
}  // namespace mallet
