// Eq. 1 against an independent long-double evaluation, with Table 1 loaded from the
// shipped config/materials.toml.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/config/materials_config.hpp"
#include "core/visual_vibration.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

// Written from the equation, not from the code: Q(t) = A·v·e^(−B·t)·sin(2π·f·t).
long double reference_eq1(const VibrationParams& p, double v, long double t) {
  return static_cast<long double>(p.amplitude) * v * std::exp(-static_cast<long double>(p.decay_per_s) * t) *
         std::sin(2.0L * std::numbers::pi_v<long double> * static_cast<long double>(p.freq_hz) * t);
}

MaterialLibrary shipped() { return config::load_materials(test::config_dir() / "materials.toml"); }

TEST(Table1, ShippedMaterialsHoldThePapersValues) {
  const MaterialLibrary lib = shipped();
  const Material* wood = lib.find("wood");
  const Material* metal = lib.find("metal");
  ASSERT_NE(wood, nullptr);
  ASSERT_NE(metal, nullptr);
  EXPECT_EQ(wood->visual, (VibrationParams{0.009, 8.0, 5.0}));
  EXPECT_EQ(metal->visual, (VibrationParams{0.020, 9.0, 15.0}));
  EXPECT_EQ(wood->actuator, (VibrationParams{1.0, 80.0, 100.0}));
  EXPECT_EQ(metal->actuator, (VibrationParams{2.0, 90.0, 300.0}));
  for (const char* name : {"rubber", "wall_wood", "aluminium"}) EXPECT_NE(lib.find(name), nullptr) << name;
}

TEST(Eq1, MatchesLongDoubleReferenceForEveryShippedTriple) {
  const MaterialLibrary lib = shipped();
  for (const Material& m : lib.all()) {
    for (const VibrationParams* p : {&m.visual, &m.actuator}) {
      for (double v : {0.1, 1.0, 2.5, 7.0}) {
        for (Nanos t = 0; t < 2 * kNanosPerSecond; t += 1'234'567) {
          const long double want = reference_eq1(*p, v, static_cast<long double>(t) * 1e-9L);
          const double scale = p->amplitude * v;
          ASSERT_NEAR(eq1(*p, v, t), static_cast<double>(want), 1e-12 * scale) << m.name << " t=" << t;
        }
      }
    }
  }
}

TEST(Eq1, StartsAtZeroAndMovesAwayFromTheSurface) {
  const VibrationParams wood{0.009, 8.0, 5.0};
  EXPECT_EQ(eq1(wood, 1.0, 0), 0.0);
  EXPECT_GT(eq1(wood, 1.0, 10'000'000), 0.0);   // 10 ms: first half cycle is positive
  EXPECT_LT(eq1(wood, 1.0, 150'000'000), 0.0);  // 150 ms: second half cycle dips below
  EXPECT_EQ(eq1(wood, 1.0, -1), 0.0);           // nothing before the impact
}

TEST(Eq1, AmplitudeIsLinearInImpactSpeed) {
  const VibrationParams metal{0.020, 9.0, 15.0};
  const Nanos t = 12'345'678;
  EXPECT_DOUBLE_EQ(eq1(metal, 3.0, t), 3.0 * eq1(metal, 1.0, t));
  // Peak of the first half cycle is close to A·v: A(v) gives metres per m/s.
  const double peak = eq1(metal, 1.0, kNanosPerSecond / 60);  // quarter period of 15 Hz (to 1 ns)
  EXPECT_NEAR(peak, 0.020 * std::exp(-9.0 / 60.0), 1e-9);
}

TEST(VisualVibration, SignedByDefaultRectifiedOnRequest) {
  const VibrationParams wood{0.009, 8.0, 5.0};
  Impact impact;
  impact.t_ns = 5 * kNanosPerSecond;
  impact.speed_m_per_s = 2.0;
  VisualVibration signed_bounce;
  VisualVibration rectified(BounceMode::rectified);
  signed_bounce.start(impact, wood);
  rectified.start(impact, wood);
  const Nanos dip = impact.t_ns + 150'000'000;
  EXPECT_LT(signed_bounce.offset_m(dip), 0.0);
  EXPECT_DOUBLE_EQ(rectified.offset_m(dip), -signed_bounce.offset_m(dip));
  EXPECT_EQ(signed_bounce.offset_m(impact.t_ns - 1), 0.0);
}

TEST(VisualVibration, ANewImpactRestartsTheBounce) {
  const VibrationParams metal{0.020, 9.0, 15.0};
  VisualVibration vib;
  Impact first;
  first.t_ns = 0;
  first.speed_m_per_s = 1.0;
  vib.start(first, metal);
  Impact second = first;
  second.t_ns = 40'000'000;
  second.speed_m_per_s = 0.5;
  vib.start(second, metal);
  EXPECT_EQ(vib.offset_m(second.t_ns), 0.0);
  EXPECT_DOUBLE_EQ(vib.offset_m(second.t_ns + 7'000'000), eq1(metal, 0.5, 7'000'000));
}

}  // namespace
}  // namespace mallet
