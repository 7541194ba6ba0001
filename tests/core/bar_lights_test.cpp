// The bars a visitor sees lit: the one under the hovering mallet, the one just struck.
#include "core/bar_lights.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace mallet {
namespace {

Vec2 above(const Target& t, double x, double gap, const Scene& s) { return {x, t.top_y + s.mallet_radius_m + gap}; }

//! A strike on `bar` at `t_ns` at `speed` m/s.
Impact impact_on(const Target& bar, Nanos t_ns, double speed) {
  Impact i;
  i.t_ns = t_ns;
  i.target = bar.id;
  i.material = bar.material;
  i.speed_m_per_s = speed;
  return i;
}

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
  const Impact hard = impact_on(bar, 1'000'000'000, 2.5);
  v.start(hard, s.materials.at(static_cast<std::size_t>(bar.material)).visual);
  EXPECT_EQ(v.target(), bar.id);
  EXPECT_EQ(v.glow(hard.t_ns - 1), 0.0);
  EXPECT_DOUBLE_EQ(v.glow(hard.t_ns), 1.0);
  // Of e^(−B·t) on the int64 clock: after 100 ms, and after a month of uptime the same.
  EXPECT_NEAR(v.glow(hard.t_ns + 100'000'000), VisualVibration::glow_of_envelope(std::exp(-b * 0.1)), 1e-12);
  // A soft strike glows less.
  Impact soft = hard;
  soft.speed_m_per_s = 0.3;
  VisualVibration w;
  w.start(soft, s.materials.at(static_cast<std::size_t>(bar.material)).visual);
  EXPECT_DOUBLE_EQ(w.glow(soft.t_ns), 0.25);

  const BarLights lights = bar_lights(s, {0.0, 0.3}, v, hard.t_ns + 50'000'000);
  EXPECT_EQ(lights[0].target, -1);  // the mallet high above everything
  EXPECT_EQ(lights[1].target, bar.id);
  EXPECT_NEAR(lights[1].glow, VisualVibration::glow_of_envelope(std::exp(-b * 0.05)), 1e-6);
  // Faded below one step of 8-bit colour: not lit at all.
  EXPECT_EQ(bar_lights(s, {0.0, 0.3}, v, hard.t_ns + 2'000'000'000)[1].target, -1);
}

TEST(BarLights, AStruckBarGlowsInSightForAThirdOfASecondAndGoesOutWithEq1sEnvelope) {
  // A visitor without sound must catch it: a hard strike's glow is still above a quarter of
  // its peak 0.3 s after, on wood and on metal (e^(−B·t) itself is below a tenth there).
  // It never brightens again, it is out once the envelope falls below kGlowEnvelopeFloor,
  // and it is a function of the envelope alone: metal's larger B fades it sooner in
  // proportion, reaching any glow at B_wood / B_metal of wood's time.
  const Scene& s = test::percussion();
  const double floor_db = std::log(VisualVibration::kGlowEnvelopeFloor);
  std::vector<double> decays;
  for (const Instrument& inst : s.instruments) {
    const Target& bar = s.targets.at(static_cast<std::size_t>(inst.targets.front()));
    const VibrationParams& visual = s.materials.at(static_cast<std::size_t>(bar.material)).visual;
    ASSERT_GT(visual.decay_per_s, 0.0) << inst.name;
    decays.push_back(visual.decay_per_s);
    VisualVibration v;
    const Impact hard = impact_on(bar, 5'000'000'000, 2.0);
    v.start(hard, visual);
    EXPECT_DOUBLE_EQ(v.glow(hard.t_ns), 1.0) << inst.name;
    EXPECT_GT(v.glow(hard.t_ns + 300'000'000), 0.25) << inst.name;
    EXPECT_LT(std::exp(-visual.decay_per_s * 0.3), 0.1) << inst.name;
    double before = v.glow(hard.t_ns);
    for (Nanos t = 1'000'000; t <= 2'000'000'000; t += 1'000'000) {
      const double now = v.glow(hard.t_ns + t);
      ASSERT_LE(now, before) << inst.name << " at " << t << " ns";
      before = now;
    }
    // Out where the envelope reaches the floor (1 ms on either side of it).
    const auto out_ns = static_cast<Nanos>(-floor_db / visual.decay_per_s * 1e9);
    EXPECT_GT(v.glow(hard.t_ns + out_ns - 1'000'000), 0.0) << inst.name;
    EXPECT_EQ(v.glow(hard.t_ns + out_ns + 1'000'000), 0.0) << inst.name;
    EXPECT_EQ(bar_lights(s, {0.0, 0.3}, v, hard.t_ns + out_ns + 1'000'000)[1].target, -1) << inst.name;
  }
  ASSERT_EQ(decays.size(), 2u);
  ASSERT_NE(decays[0], decays[1]);
  for (double t : {0.05, 0.1, 0.2, 0.3, 0.45}) {
    EXPECT_NEAR(VisualVibration::glow_of_envelope(std::exp(-decays[0] * t)),
                VisualVibration::glow_of_envelope(std::exp(-decays[1] * (t * decays[0] / decays[1]))), 1e-12);
  }
  EXPECT_EQ(VisualVibration::glow_of_envelope(0.0), 0.0);
  EXPECT_EQ(VisualVibration::glow_of_envelope(1.0), 1.0);
}

TEST(BarLights, EachMaterialGlowsInItsOwnColour) {
  // Amber on the wood, steel blue on the metal (config/materials.toml, glow_srgb): the
  // wood's glow warmer than it is cool, the metal's the other way round.
  const Scene& s = test::percussion();
  for (const Instrument& inst : s.instruments) {
    const Material& m = s.materials.at(static_cast<std::size_t>(inst.material));
    const std::array<double, 3>& c = m.glow_srgb;
    if (m.name == "wood") {
      EXPECT_GT(c[0], c[2] + 0.5) << inst.name;
    } else {
      ASSERT_EQ(m.name, "metal");
      EXPECT_GT(c[2], c[0] + 0.2) << inst.name;
      EXPECT_GE(c[2], 0.9) << inst.name;  // bright
    }
  }
}

TEST(BarLights, TheOtherScenesHaveNoBarsToLight) {
  const Scene& wall = test::wall();
  const Target& t = wall.targets.at(0);
  EXPECT_EQ(bar_under(wall, above(t, (t.x_min + t.x_max) / 2, 0.03, wall)), -1);
}

}  // namespace
}  // namespace mallet
