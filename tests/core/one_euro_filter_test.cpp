// The 1€ pointer filter (Casiez, Roussel & Vogel, CHI 2012).
#include "core/one_euro_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace mallet {
namespace {

constexpr Nanos kStep = 10'000'000;  // 100 Hz, the Wii camera's rate

double stddev(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m += x;
  m /= double(v.size());
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size()));
}

TEST(OneEuroFilter, ConstantInputConvergesToIt) {
  OneEuroFilter f({1.0, 50.0, 1.0});
  EXPECT_FALSE(f.value());
  std::optional<Vec2> out;
  for (int i = 0; i < 500; ++i) out = f.update(i * kStep, {0.123, -0.04});
  ASSERT_TRUE(out);
  EXPECT_NEAR(out->x, 0.123, 1e-12);
  EXPECT_NEAR(out->y, -0.04, 1e-12);
  // And after a step to a new constant, it gets there too.
  for (int i = 500; i < 1500; ++i) out = f.update(i * kStep, {0.2, 0.1});
  EXPECT_NEAR(out->x, 0.2, 1e-9);
  EXPECT_NEAR(out->y, 0.1, 1e-9);
}

TEST(OneEuroFilter, StillNoisyInputJitterShrinks) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.0005);  // 0.5 mm
  OneEuroFilter f({1.0, 50.0, 1.0});
  std::vector<double> raw, filtered;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p{0.1 + noise(rng), 0.05 + noise(rng)};
    const Vec2 out = *f.update(i * kStep, p);
    if (i < 200) continue;  // settle
    raw.push_back(p.x);
    filtered.push_back(out.x);
  }
  EXPECT_LT(stddev(filtered), 0.5 * stddev(raw));
}

//! Steady-state lag (s) of the filter behind a ramp at `speed` m/s along x.
double ramp_lag_s(double beta, double speed) {
  OneEuroFilter f({1.0, beta, 1.0});
  Vec2 out{};
  const int n = 400;
  for (int i = 0; i < n; ++i) out = *f.update(i * kStep, {speed * i * 0.01, 0.0});
  const double truth = speed * (n - 1) * 0.01;
  EXPECT_LT(out.x, truth);  // behind, never ahead
  return (truth - out.x) / speed;
}

TEST(OneEuroFilter, RampIsFollowedWithBoundedLagThatShrinksWithBeta) {
  const double lag0 = ramp_lag_s(0.0, 1.0);
  const double lag10 = ramp_lag_s(10.0, 1.0);
  const double lag100 = ramp_lag_s(100.0, 1.0);
  // beta = 0 is a plain 1 Hz low-pass: lag ≈ τ − dt·(1 − α)/α ≈ 0.15 s, bounded.
  EXPECT_GT(lag0, 0.1);
  EXPECT_LT(lag0, 0.2);
  EXPECT_LT(lag10, lag0);
  EXPECT_LT(lag100, lag10);
  EXPECT_LT(lag100, 0.005);
  // The speed estimate: from the raw previous sample it settles on the ramp's speed; from
  // the filtered previous value (the default) it also carries the lag, so it reads more.
  OneEuroFilter raw_d({1.0, 10.0, 1.0, true});
  OneEuroFilter filtered_d({1.0, 10.0, 1.0});
  for (int i = 0; i < 1000; ++i) {
    raw_d.update(i * kStep, {0.0, -0.5 * i * 0.01});
    filtered_d.update(i * kStep, {0.0, -0.5 * i * 0.01});
  }
  EXPECT_NEAR(raw_d.velocity().y, -0.5, 1e-3);
  EXPECT_NEAR(raw_d.velocity().x, 0.0, 1e-12);
  // In steady state the lag is v·dt·(1 − α)/α, so the estimate reads v/α.
  EXPECT_NEAR(filtered_d.velocity().y, -0.5 / one_euro_alpha(filtered_d.last_cutoff_hz(), 0.01), 1e-3);
  EXPECT_LT(filtered_d.velocity().y, -0.5);
}

TEST(OneEuroFilter, ZeroDtAndNonFiniteSamplesAreIgnoredAndCounted) {
  OneEuroFilter f({1.0, 50.0, 1.0});
  f.update(0, {0.0, 0.0});
  f.update(kStep, {0.01, 0.0});
  const Vec2 before = *f.value();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(*f.update(kStep, {0.5, 0.5}), before);       // dt = 0
  EXPECT_EQ(*f.update(kStep / 2, {0.5, 0.5}), before);   // dt < 0
  EXPECT_EQ(*f.update(2 * kStep, {nan, 0.0}), before);
  EXPECT_EQ(*f.update(2 * kStep, {0.0, inf}), before);
  EXPECT_EQ(f.counters().ignored_not_after_previous, 2u);
  EXPECT_EQ(f.counters().ignored_non_finite, 2u);
  EXPECT_EQ(f.counters().accepted, 2u);
  const Vec2 after = *f.update(2 * kStep, {0.02, 0.0});
  EXPECT_TRUE(std::isfinite(after.x) && std::isfinite(after.y));
  EXPECT_TRUE(std::isfinite(f.velocity().x));
  // A NaN first sample does not prime the filter.
  OneEuroFilter g;
  EXPECT_FALSE(g.update(0, {nan, nan}));
  EXPECT_EQ(g.counters().ignored_non_finite, 1u);
}

TEST(OneEuroFilter, ThirtyDaysOfUptimeBehaveTheSame) {
  const Nanos month = Nanos{30} * 24 * 3600 * kNanosPerSecond;
  OneEuroFilter a({1.0, 20.0, 1.0}), b({1.0, 20.0, 1.0});
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.001);
  for (int i = 0; i < 3000; ++i) {
    const Vec2 p{0.3 * std::sin(i * 0.02) + noise(rng), 0.1 * std::cos(i * 0.05) + noise(rng)};
    const Nanos t = i * kStep + (i % 3) * 137'000;  // uneven spacing
    const Vec2 ra = *a.update(t, p);
    const Vec2 rb = *b.update(month + t, p);
    ASSERT_EQ(ra, rb) << "sample " << i;  // bit-identical: only differences become doubles
  }
}

TEST(OneEuroFilter, ResetForgetsTheState) {
  OneEuroFilter f({1.0, 50.0, 1.0});
  for (int i = 0; i < 100; ++i) f.update(i * kStep, {0.1 * i, 0.0});
  f.reset();
  EXPECT_FALSE(f.value());
  EXPECT_EQ(f.velocity(), (Vec2{0, 0}));
  // The next sample passes through, even at an earlier time (a new track).
  EXPECT_EQ(*f.update(5, {-0.2, 0.3}), (Vec2{-0.2, 0.3}));
  EXPECT_EQ(f.counters().accepted, 101u);
}

TEST(OneEuroFilter, BadConfigIsRefused) {
  EXPECT_TRUE(validate(OneEuroConfig{}));
  EXPECT_FALSE(validate(OneEuroConfig{0.0, 1.0, 1.0}));
  EXPECT_FALSE(validate(OneEuroConfig{1.0, -1.0, 1.0}));
  EXPECT_FALSE(validate(OneEuroConfig{1.0, 1.0, std::nan("")}));
  EXPECT_THROW(OneEuroFilter(OneEuroConfig{-1.0, 0.0, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace mallet
