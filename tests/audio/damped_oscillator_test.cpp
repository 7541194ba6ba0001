// The oscillator behind every voice stays on Eq. 1: within 1e-6 of the exact value for
// 10 minutes, undamped or near Nyquist, and fits back to Table 1 within 1%.
#include <cfloat>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "audio/damped_oscillator.hpp"
#include "audio/denormals.hpp"
#include "core/damped_sine_fit.hpp"

namespace mallet::audio {
namespace {

long double exact(double a, double b, double f, long double t) {
  return a * std::exp(-static_cast<long double>(b) * t) *
         std::sin(2.0L * std::numbers::pi_v<long double> * static_cast<long double>(f) * t);
}

// Ticks for `seconds` and compares every 97th sample with the long-double formula.
double max_error(double a, double b, double f, double delay, int fs, double seconds) {
  DampedOscillator osc;
  osc.start(a, b, f, delay, fs);
  const auto n = static_cast<std::int64_t>(seconds * fs);
  double worst = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const double y = osc.tick();
    if (i % 97 == 0 || i == n - 1) {
      const long double t = static_cast<long double>(i) / fs + delay;
      worst = std::max(worst, static_cast<double>(std::fabs(y - exact(a, b, f, t))));
    }
  }
  return worst;
}

TEST(DampedOscillator, UndampedStaysWithinOneMillionthForTenMinutes) {
  EXPECT_LT(max_error(1.0, 0.0, 300.0, 7e-6, 48000, 600.0), 1e-6);
}

TEST(DampedOscillator, NearNyquistUndampedStaysWithinOneMillionthForTenMinutes) {
  EXPECT_LT(max_error(1.0, 0.0, 23999.5, 3e-6, 48000, 600.0), 1e-6);
}

TEST(DampedOscillator, TableOneActuatorTriplesAreExactAndFitBack) {
  struct Triple {
    double a, b, f;
  } triples[] = {{1.0, 80.0, 100.0}, {2.0, 90.0, 300.0}};
  for (const Triple& t : triples) {
    EXPECT_LT(max_error(t.a, t.b, t.f, 1.5e-5, 48000, 2.0), 1e-9 * t.a);
    DampedOscillator osc;
    osc.start(t.a, t.b, t.f, 0.0, 48000);
    std::vector<double> y(24000);
    for (double& s : y) s = osc.tick();
    const DampedSineFit fit = fit_damped_sine(y, 48000);
    ASSERT_TRUE(fit.ok);
    EXPECT_NEAR(fit.decay_per_s, t.b, 0.01 * t.b);
    EXPECT_NEAR(fit.freq_hz, t.f, 0.01 * t.f);
    EXPECT_NEAR(fit.amplitude, t.a, 0.01 * t.a);
  }
}

TEST(DampedOscillator, HeavyDecayEndsInExactZerosNotSubnormals) {
  DampedOscillator osc;
  osc.start(1.0, 1e4, 300.0, 0.0, 48000);
  for (int i = 0; i < 48000; ++i) {
    const double y = osc.tick();
    ASSERT_TRUE(y == 0.0 || std::fabs(y) >= DBL_MIN) << i;  // never subnormal
  }
  EXPECT_EQ(osc.envelope(), 0.0);
}

TEST(DampedOscillator, BlockRenderingEqualsTickByTick) {
  DampedOscillator a, b;
  a.start(0.7, 80.0, 100.0, 3e-6, 48000);
  b.start(0.7, 80.0, 100.0, 3e-6, 48000);
  std::vector<double> blocks(5000, 0.0);
  for (int first = 0, n = 1; first < 5000; first += n, n = n % 300 + 7) b.add_to(blocks.data() + first, std::min(n, 5000 - first));
  for (int i = 0; i < 5000; ++i) ASSERT_EQ(blocks[static_cast<std::size_t>(i)], a.tick()) << i;
}

TEST(Denormals, FlushedInsideTheScopeRestoredAfter) {
  const bool before = ScopedFlushDenormals::active();
  {
    ScopedFlushDenormals ftz;
    EXPECT_TRUE(ScopedFlushDenormals::active());
    volatile double tiny = 1e-300;
    volatile double r = tiny * 1e-10;  // subnormal result → flushed to zero
    EXPECT_EQ(r, 0.0);
  }
  EXPECT_EQ(ScopedFlushDenormals::active(), before);
}

}  // namespace
}  // namespace mallet::audio
