// The bars a visitor sees lit: the one under the hovering mallet, the one just struck.
#include "core/bar_lights.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace mallet {
namespace {

Vec2 above(const Target& t, double x, double gap, const Scene& s) { return {x, t.top_y + s.mallet_radius_m + gap}; }

TEST(BarLights, TheBarUnderTheHoveringMalletIsTheOneItWouldStrike) {
  const Scene& s = test::percussion();
  const Target& a = s.targets.at(2);
  const Target& b = s.targets.at(3);
  const double middle = (a.x_min + a.x_max) / 2;
  EXPECT_EQ(bar_under(s, above(a, middle, 0.05, s)), a.id);
  // Within a mallet radius of its edge, as the contact solver reaches (the xylophone's last
  // bar, nothing beyond it); in the gap between two bars, the nearer one.
  const Target& last = s.targets.at(static_cast<std::size_t>(s.instruments.at(0).targets.back()));
  EXPECT_EQ(bar_under(s, above(last, last.x_max + 0.8 * s.mallet_radius_m, 0.05, s)), last.id);
  const double gap_middle = (a.x_max + b.x_min) / 2;
  EXPECT_EQ(bar_under(s, above(a, gap_middle - 1e-4, 0.05, s)), a.id);
  EXPECT_EQ(bar_under(s, above(a, gap_middle + 1e-4, 0.05, s)), b.id);
  // Too high above it, or below its top (resting on it, or struck through): not hovering.
  EXPECT_EQ(bar_under(s, above(a, middle, kHoverHeightM + 0.01, s)), -1);
  EXPECT_EQ(bar_under(s, above(a, middle, -0.005, s)), -1);
  // Beyond the instruments' ends.
  EXPECT_EQ(bar_under(s, above(a, s.targets.front().x_min - 2 * s.mallet_radius_m, 0.05, s)), -1);
}

TEST(BarLights, AStruckBarGlowsAndFadesWithItsMaterialsVisualDecay) {
  const Scene& s = test::percussion();
  const Target& bar = s.targets.at(11);
  const double b = s.materials.at(static_cast<std::size_t>(bar.material)).visual.decay_per_s;
  // Before any impact nothing glows.
  EXPECT_EQ(bar_lights(s, {0.0, 0.3}, VisualVibration{}, 0)[1].target, -1);
  VisualVibration v;
  Impact hard;
  hard.t_ns = 1'000'000'000;
  hard.target = bar.id;
  hard.material = bar.material;
  hard.speed_m_per_s = 2.5;
  v.start(hard, s.materials.at(static_cast<std::size_t>(bar.material)).visual);
  EXPECT_EQ(v.target(), bar.id);
  EXPECT_EQ(v.glow(hard.t_ns - 1), 0.0);
  EXPECT_DOUBLE_EQ(v.glow(hard.t_ns), 1.0);
  // e^(−B·t) on the int64 clock: after 100 ms, and after a month of uptime the same.
  EXPECT_NEAR(v.glow(hard.t_ns + 100'000'000), std::exp(-b * 0.1), 1e-12);
  // A soft strike glows less.
  Impact soft = hard;
  soft.speed_m_per_s = 0.3;
  VisualVibration w;
  w.start(soft, s.materials.at(static_cast<std::size_t>(bar.material)).visual);
  EXPECT_DOUBLE_EQ(w.glow(soft.t_ns), 0.25);

  const std::array<BarLight, 2> lights = bar_lights(s, {0.0, 0.3}, v, hard.t_ns + 50'000'000);
  EXPECT_EQ(lights[0].target, -1);  // the mallet high above everything
  EXPECT_EQ(lights[1].target, bar.id);
  EXPECT_NEAR(lights[1].glow, std::exp(-b * 0.05), 1e-6);
  // Faded below one step of 8-bit colour: not lit at all.
  EXPECT_EQ(bar_lights(s, {0.0, 0.3}, v, hard.t_ns + 2'000'000'000)[1].target, -1);
}

TEST(BarLights, TheOtherScenesHaveNoBarsToLight) {
  const Scene& wall = test::wall();
  const Target& t = wall.targets.at(0);
  EXPECT_EQ(bar_under(wall, above(t, (t.x_min + t.x_max) / 2, 0.03, wall)), -1);
}

}  // namespace
}  // namespace mallet
