// The output limiter alone: never above its ceiling for any input (a full-scale square, a
// single-sample spike, ±inf, NaN), the input bit for bit below its threshold, no delay,
// and back to bit-exact once the hold and the release are over.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "audio/peak_limiter.hpp"

namespace mallet::audio {
namespace {

constexpr int kLimiterRate = 48000;

TEST(PeakLimiter, BelowTheThresholdTheOutputIsTheInputBitForBit) {
  PeakLimiter limiter(0.9, kLimiterRate);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> level(-0.9, 0.9);
  for (int i = 0; i < 100000; ++i) {
    const double x = level(random);
    ASSERT_EQ(limiter.tick(x), x) << i;
    ASSERT_FALSE(limiter.limiting());
  }
  EXPECT_EQ(limiter.tick(0.9), 0.9);  // the threshold itself passes
  EXPECT_EQ(limiter.tick(-0.9), -0.9);
}

TEST(PeakLimiter, AFullScaleSquareStaysUnderTheCeiling) {
  for (double height : {1.0, 4.0, 1e3, 1e9}) {
    PeakLimiter limiter(0.9, kLimiterRate);
    double peak = 0;
    int over_threshold = 0;
    for (int i = 0; i < kLimiterRate; ++i) {
      const double x = (i / 24) % 2 ? height : -height;  // 1 kHz
      const auto y = static_cast<float>(limiter.tick(x));
      peak = std::max(peak, static_cast<double>(std::fabs(y)));
      over_threshold += std::fabs(y) > 0.9f;
      ASSERT_LE(std::fabs(y), static_cast<float>(PeakLimiter::kCeiling)) << height << " sample " << i;
      ASSERT_TRUE(std::signbit(y) == std::signbit(x)) << "the limiter never inverts: " << i;
    }
    EXPECT_LT(peak, 1.0) << height;
    EXPECT_GT(peak, 0.9) << height;          // it limits, it does not mute
    EXPECT_GT(over_threshold, 0) << height;  // the shoulder above the threshold is used
  }
}

TEST(PeakLimiter, ASingleSampleSpikeIsCaughtOnItsOwnSampleThenReleased) {
  PeakLimiter limiter(0.9, kLimiterRate);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(limiter.tick(0.5), 0.5);
  const double spike = limiter.tick(50.0);
  EXPECT_LE(spike, PeakLimiter::kCeiling);
  EXPECT_GT(spike, 0.9);  // on the spike's own sample: no delay, no look-ahead
  // The gain is held, then released: the next samples are turned down, never up.
  const double held = limiter.tick(0.5);
  EXPECT_LT(held, 0.5);
  EXPECT_GT(held, 0.0);
  double last = held;
  const int hold = static_cast<int>(std::ceil(PeakLimiter::kHoldS * kLimiterRate));
  for (int i = 1; i < hold; ++i) ASSERT_EQ(limiter.tick(0.5), held) << "held " << i;
  for (int i = 0; i < kLimiterRate && limiter.limiting(); ++i) {
    const double y = limiter.tick(0.5);
    ASSERT_GE(y, last) << "release " << i;  // recovers monotonically
    ASSERT_LE(y, 0.5);
    last = y;
  }
  // 50 → 0.9 at a 100 ms time constant: ln(50/0.9)·0.1 s ≈ 0.4 s; then exact again.
  EXPECT_FALSE(limiter.limiting());
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(limiter.tick(0.5), 0.5) << i;
}

TEST(PeakLimiter, NoInputEscapesTheCeiling) {
  PeakLimiter limiter(0.5, kLimiterRate);
  const double inf = std::numeric_limits<double>::infinity();
  for (double x : {inf, -inf, std::numeric_limits<double>::max(), -1e300, 0.7, -0.99, 1e-300}) {
    const double y = limiter.tick(x);
    EXPECT_TRUE(std::isfinite(y)) << x;
    EXPECT_LE(std::fabs(y), PeakLimiter::kCeiling) << x;
    EXPECT_EQ(std::signbit(y), std::signbit(x)) << x;
  }
  EXPECT_EQ(limiter.tick(std::numeric_limits<double>::quiet_NaN()), 0.0);
  // Random loud noise, any level: the bound holds on every sample, after the float conversion.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> level(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const double x = level(random) * std::pow(10.0, 6.0 * (i % 97) / 97.0);
    ASSERT_LE(std::fabs(static_cast<float>(limiter.tick(x))), static_cast<float>(PeakLimiter::kCeiling)) << i;
  }
}

TEST(PeakLimiter, ALoudNoteKeepsItsWaveformAfterItsFirstPeak) {
  // A decaying 440 Hz sinusoid at 4× full scale: after the first quarter-cycle the gain
  // moves slowly, so the output is the input times a near-constant gain (not a square wave).
  PeakLimiter limiter(0.9, kLimiterRate);
  std::vector<double> x(kLimiterRate / 4), y(x.size()), g(x.size());
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double t = static_cast<double>(n) / kLimiterRate;
    x[n] = 4.0 * std::exp(-3.0 * t) * std::sin(2 * 3.141592653589793 * 440 * t);
    y[n] = limiter.tick(x[n]);
    g[n] = limiter.gain();
  }
  for (std::size_t n = 60; n + 1 < x.size(); ++n) {  // past the first peak (sample 27)
    ASSERT_NEAR(y[n], x[n] * g[n], 1e-12);
    // < 0.5 % a sample (a per-sample clip would swing from 1 to 0.25 within each cycle);
    // the largest steps are where the released envelope meets a rising edge again.
    ASSERT_NEAR(g[n + 1], g[n], 0.005 * g[n]) << n;
  }
  EXPECT_LT(*std::max_element(g.begin() + 60, g.end()), 1.0);  // limiting all along
}

TEST(PeakLimiter, RefusesAThresholdAtOrAboveItsCeiling) {
  EXPECT_THROW(PeakLimiter(PeakLimiter::kCeiling, kLimiterRate), std::invalid_argument);
  EXPECT_THROW(PeakLimiter(0.0, kLimiterRate), std::invalid_argument);
  EXPECT_THROW(PeakLimiter(0.9, 0), std::invalid_argument);
  EXPECT_NO_THROW(PeakLimiter(kMaxSoftClipKnee, kLimiterRate));  // every knee the settings allow
  EXPECT_NO_THROW(PeakLimiter(kMinSoftClipKnee, kLimiterRate));
}

}  // namespace
}  // namespace mallet::audio
