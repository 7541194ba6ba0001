// What a frame changes on the screen (render/frame_damage.hpp): the bookkeeping that lets a
// still scene draw nothing and a moving one draw only where it moves. The pixels themselves
// are checked against whole frames in background_cache_test.cpp.
#include <gtest/gtest.h>

#include "render/frame_damage.hpp"

namespace mallet::render {
namespace {

FrameLook look(double mallet_x_px) {
  FrameLook l;
  l.width = 640;
  l.height = 360;
  l.mallet = true;
  l.mallet_px = {mallet_x_px, 100};
  const int x = static_cast<int>(mallet_x_px);
  l.mallet_rect = {x - 20, 80, x + 20, 130};
  return l;
}

bool same(const PixelRect& a, const PixelRect& b) {
  return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1;
}

TEST(FrameDamage, TheFirstFrameAndAnImageOfUnknownContentAreDrawnWhole) {
  FrameDamage d;
  EXPECT_TRUE(d.changes(look(100)));
  EXPECT_TRUE(same(d.commit(look(100), 1), {0, 0, 640, 360}));  // nothing committed before it
  EXPECT_TRUE(same(d.commit(look(200), 0), {0, 0, 640, 360}));  // age 0: unknown content
}

TEST(FrameDamage, AStillFrameChangesNothing) {
  FrameDamage d;
  d.commit(look(100), 0);
  EXPECT_FALSE(d.changes(look(100)));
  EXPECT_TRUE(d.commit(look(100), 1).empty());
}

TEST(FrameDamage, AMovedHeadChangesWhereItWasAndWhereItIs) {
  FrameDamage d;
  d.commit(look(100), 0);
  EXPECT_TRUE(d.changes(look(300)));
  EXPECT_TRUE(same(d.commit(look(300), 1), {80, 80, 320, 130}));
}

TEST(FrameDamage, AnOlderImageGetsEveryChangeSinceItsFrame) {
  FrameDamage d;
  d.commit(look(100), 0);  // frame 0
  d.commit(look(200), 1);  // frame 1: 80..220
  d.commit(look(200), 1);  // frame 2: nothing
  // Frame 3 into the image that holds frame 0: frames 1, 2 and 3's changes.
  EXPECT_TRUE(same(d.commit(look(400), 3), {80, 80, 420, 130}));
  // Into one that holds frame 3: frame 4's alone.
  EXPECT_TRUE(same(d.commit(look(410), 1), {380, 80, 430, 130}));
  // Older than the history kept, or older than the first frame: whole.
  EXPECT_TRUE(same(d.commit(look(410), FrameDamage::kHistory + 1), {0, 0, 640, 360}));
  EXPECT_TRUE(same(d.commit(look(410), 7), {0, 0, 640, 360}));
}

TEST(FrameDamage, AHeadDriftingUnderARasterStepStaysUntilItsDriftAddsUpToOne) {
  FrameDamage d;
  d.commit(look(100), 0);
  const double step = kStillMalletPx * 0.4;
  EXPECT_FALSE(d.changes(look(100 + step)));
  EXPECT_TRUE(d.commit(look(100 + step), 1).empty());
  EXPECT_TRUE(d.commit(look(100 + 2 * step), 1).empty());
  EXPECT_EQ(d.drawn().mallet_px.x, 100);  // drawn where it was
  // Measured from where it was drawn, not from the frame before: the third small step moves it.
  EXPECT_TRUE(d.changes(look(100 + 3 * step)));
  EXPECT_FALSE(d.commit(look(100 + 3 * step), 1).empty());
}

TEST(FrameDamage, AFadingGlowIsRedrawnOnlyWhenItHasChangedByAStep) {
  FrameDamage d;
  FrameLook a = look(100);
  a.lights = {BarLight{5, 0.5f}, BarLight{}};
  a.light_rects = {PixelRect{500, 210, 530, 290}, PixelRect{}};
  d.commit(a, 0);
  FrameLook b = a;
  b.lights[0].glow = 0.5f - 0.4f * kStillGlow;  // under a step: the image keeps its glow
  EXPECT_FALSE(d.changes(b));
  EXPECT_TRUE(d.commit(b, 1).empty());
  EXPECT_EQ(d.drawn().lights[0].glow, 0.5f);  // what the renderer draws the bar with
  FrameLook c = a;
  c.lights[0].glow = 0.5f - 1.2f * kStillGlow;  // a step from the glow drawn: the bar again
  EXPECT_TRUE(same(d.commit(c, 1), {500, 210, 530, 290}));
  EXPECT_EQ(d.drawn().lights[0].glow, c.lights[0].glow);
  // Going out is always drawn, however small the last glow was.
  FrameLook dim = c;
  dim.lights[0].glow = 0.004f;
  d.commit(dim, 1);
  FrameLook out = dim;
  out.lights[0] = BarLight{};
  out.light_rects[0] = PixelRect{};
  EXPECT_TRUE(same(d.commit(out, 1), {500, 210, 530, 290}));
  // A whole frame is drawn exactly, even a change under a step.
  FrameLook e = dim;
  d.commit(e, 0);
  e.lights[0].glow = 0.004f - 0.1f * kStillGlow;
  d.commit(e, 0);
  EXPECT_EQ(d.drawn().lights[0].glow, e.lights[0].glow);
}

TEST(FrameDamage, ALightThatChangesChangesItsBarAlone) {
  FrameDamage d;
  FrameLook a = look(100);
  a.lights = {BarLight{3, 0.2f}, BarLight{}};
  a.light_rects = {PixelRect{400, 200, 440, 300}, PixelRect{}};
  d.commit(a, 0);
  FrameLook b = a;
  b.lights[1] = BarLight{5, 0.9f};
  b.light_rects[1] = PixelRect{500, 210, 530, 290};
  EXPECT_TRUE(same(d.commit(b, 1), {500, 210, 530, 290}));
  FrameLook c = b;
  c.lights[1].glow = 0.8f;  // fading
  EXPECT_TRUE(same(d.commit(c, 1), {500, 210, 530, 290}));
  FrameLook e = c;
  e.lights = {BarLight{3, 0.2f}, BarLight{}};  // faded out: its bar as cached again
  e.light_rects = {PixelRect{400, 200, 440, 300}, PixelRect{}};
  EXPECT_TRUE(same(d.commit(e, 1), {500, 210, 530, 290}));
}

TEST(FrameDamage, TextThatChangesChangesWhereItWasAndIs) {
  FrameDamage d;
  FrameLook a = look(100);
  a.overlay_vertices = {OverlayVertex{10.5f, 20, 0, 0, {1, 1, 1, 1}}, OverlayVertex{60, 40.5f, 0, 0, {1, 1, 1, 1}}};
  a.overlay_indices = {0, 1, 0};
  d.commit(a, 0);
  FrameLook same_text = a;
  EXPECT_FALSE(d.changes(same_text));
  FrameLook b = a;
  b.overlay_vertices[1].x = 90;
  EXPECT_TRUE(same(d.commit(b, 1), {9, 19, 91, 42}));  // both boxes, a pixel of margin
  FrameLook c = b;
  c.overlay_vertices[0].color = {1, 0, 0, 1};  // a colour alone
  EXPECT_TRUE(same(d.commit(c, 1), {9, 19, 91, 42}));
}

TEST(FrameDamage, ANewSizeOrForgettingChangesEverything) {
  FrameDamage d;
  d.commit(look(100), 0);
  FrameLook bigger = look(100);
  bigger.width = 800;
  EXPECT_TRUE(same(d.commit(bigger, 1), {0, 0, 800, 360}));
  d.forget();
  EXPECT_TRUE(d.changes(bigger));
  EXPECT_TRUE(same(d.commit(bigger, 1), {0, 0, 800, 360}));
}

}  // namespace
}  // namespace mallet::render
