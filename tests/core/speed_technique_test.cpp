// The Speed technique's law, its slow-down and speed-up over a bump, and the bound on
// the cursor-hand offset after many crossings; the relief it reads.
#include "core/speed_technique.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace mallet {
namespace {

TextureRelief bump(ReliefProfile profile = ReliefProfile::cosine) {
  TextureRelief r;
  r.shape = ReliefShape::bump;
  r.profile = profile;
  r.center = {0.0, 0.0};
  r.radius_m = 0.08;
  r.height_m = 0.012;
  return r;
}

TEST(TextureRelief, ProfilesPeakAtTheCentreAndVanishAtTheRim) {
  for (ReliefProfile p : {ReliefProfile::cosine, ReliefProfile::gaussian}) {
    TextureRelief r = bump(p);
    EXPECT_NEAR(r.height_at({0, 0}), 0.012, 1e-15);
    EXPECT_NEAR(r.height_at({0.0799999, 0}), 0.0, 1e-8);
    EXPECT_EQ(r.height_at({0.08, 0}), 0.0);
    EXPECT_EQ(r.height_at({0.2, 0.1}), 0.0);
    EXPECT_TRUE(r.covers({0.05, 0.05}));
    EXPECT_FALSE(r.covers({0.06, 0.06}));
    r.shape = ReliefShape::hole;
    EXPECT_NEAR(r.height_at({0, 0}), -0.012, 1e-15);
  }
}

TEST(TextureRelief, GradientIsTheDerivativeOfTheHeight) {
  for (ReliefProfile p : {ReliefProfile::cosine, ReliefProfile::gaussian}) {
    const TextureRelief r = bump(p);
    for (Vec2 q : {Vec2{0.02, 0.01}, Vec2{-0.05, 0.03}, Vec2{0.001, -0.07}}) {
      const double h = 1e-7;
      const double gx = (r.height_at({q.x + h, q.y}) - r.height_at({q.x - h, q.y})) / (2 * h);
      const double gy = (r.height_at({q.x, q.y + h}) - r.height_at({q.x, q.y - h})) / (2 * h);
      EXPECT_NEAR(r.gradient_at(q).x, gx, 1e-6);
      EXPECT_NEAR(r.gradient_at(q).y, gy, 1e-6);
    }
  }
}

TEST(SpeedTechnique, GainLawOnASyntheticProfile) {
  const TextureRelief r = bump();
  SpeedTechniqueConfig c;
  c.slope_gain = 2.0;
  c.gain_min = 0.25;
  c.gain_max = 2.0;
  const SpeedTechnique st(r, c);
  // Cosine bump: dh/dr = −H·π/(2R)·sin(π·r/R); at r = R/2 the slope's magnitude is H·π/(2R).
  const double s = 0.012 * M_PI / (2 * 0.08);
  EXPECT_NEAR(st.gain_at({-0.04, 0}, {1, 0}), 1 - 2 * s, 1e-12);  // climbing: slower
  EXPECT_NEAR(st.gain_at({0.04, 0}, {1, 0}), 1 + 2 * s, 1e-12);   // descending: faster
  EXPECT_NEAR(st.gain_at({0.04, 0}, {0, 1}), 1.0, 1e-12);          // along a contour: unchanged
  EXPECT_EQ(st.gain_at({0.3, 0}, {1, 0}), 1.0);                    // off the disc
  // Clamping: a steep relief hits both bounds.
  TextureRelief steep = r;
  steep.height_m = 0.2;
  const SpeedTechnique st2(steep, c);
  EXPECT_EQ(st2.gain_at({-0.04, 0}, {1, 0}), 0.25);
  EXPECT_EQ(st2.gain_at({0.04, 0}, {1, 0}), 2.0);
}

TEST(SpeedTechnique, CrossingABumpSlowsTheCursorGoingUpAndSpeedsItUpGoingDown) {
  SpeedTechnique st(bump(), {});
  double min_gain_up = 1, max_gain_down = 1;
  st.update({-0.2, 0});
  for (int k = 1; k <= 4000; ++k) {  // 1 mm steps from −0.2 to +0.2 m through the centre
    const Vec2 before = st.cursor();
    st.update({-0.2 + k * 1e-4, 0});
    const double cursor_step = st.cursor().x - before.x;
    if (std::fabs(st.cursor().x) < 0.075 && std::fabs(st.cursor().x) > 0.005) {
      if (st.cursor().x < 0) min_gain_up = std::min(min_gain_up, st.gain());
      else max_gain_down = std::max(max_gain_down, st.gain());
      EXPECT_GT(cursor_step, 0.0);  // it never stops nor turns back
    }
  }
  EXPECT_LT(min_gain_up, 0.8);
  EXPECT_GT(max_gain_down, 1.2);
  // A hole is the opposite.
  TextureRelief hole = bump();
  hole.shape = ReliefShape::hole;
  const SpeedTechnique h(hole, {});
  EXPECT_GT(h.gain_at({-0.04, 0}, {1, 0}), 1.2);
  EXPECT_LT(h.gain_at({0.04, 0}, {1, 0}), 0.8);
}

TEST(SpeedTechnique, NoUnboundedDriftAfterTenThousandCrossings) {
  SpeedTechniqueConfig c;
  SpeedTechnique st(bump(ReliefProfile::gaussian), c);
  double worst = 0;
  st.update({-0.15, 0.01});
  for (int crossing = 0; crossing < 10000; ++crossing) {
    // Always left to right (the worst case: nothing cancels), in 2 mm steps (a 60 Hz
    // pointer at 0.12 m/s), then back off the texture above it.
    for (int k = 1; k <= 150; ++k) {
      st.update({-0.15 + k * 0.002, 0.01});
      worst = std::max(worst, std::hypot(st.offset().x, st.offset().y));
    }
    for (int k = 1; k <= 30; ++k) st.update({0.15 - k * 0.01, 0.1 * (k < 30)});
    st.update({-0.15, 0.01});
  }
  EXPECT_LE(worst, c.max_offset_m + 1e-12);
  // Back on flat ground after all that, the cursor is on the hand again.
  EXPECT_LT(std::hypot(st.offset().x, st.offset().y), 1e-4);
}

TEST(SpeedTechnique, AStillHandSeesAStillCursorAndBadSamplesAreIgnored) {
  SpeedTechnique st(bump(), {});
  st.update({-0.03, 0});
  st.update({-0.02, 0});
  const Vec2 c = st.cursor();
  for (int i = 0; i < 100; ++i) st.update({-0.02, 0});
  EXPECT_EQ(st.cursor(), c);
  st.update({NAN, 0});
  st.update({0, INFINITY});
  EXPECT_EQ(st.cursor(), c);
}

}  // namespace
}  // namespace mallet
