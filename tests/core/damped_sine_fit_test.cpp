// The fitter that checks stimuli against Table 1 must itself recover known parameters.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/damped_sine_fit.hpp"

namespace mallet {
namespace {

std::vector<double> synth(double a, double b, double f, double phi, double rate, double t0, std::size_t n,
                          double noise = 0.0) {
  std::mt19937 rng(42);
  std::normal_distribution<double> g(0.0, noise);
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = t0 + static_cast<double>(i) / rate;
    y[i] = a * std::exp(-b * t) * std::sin(2 * std::numbers::pi * f * t + phi) + (noise > 0 ? g(rng) : 0.0);
  }
  return y;
}

struct Case {
  double a, b, f, phi, rate, t0;
  std::size_t n;
};

TEST(DampedSineFit, RecoversTableOneTriplesExactly) {
  const Case cases[] = {
      {0.0108, 8, 5, 0, 1000, 0, 1000},            // wood visual at v = 1.2 m/s, 1 kHz trace
      {0.024, 9, 15, 0, 1000, 0.0004, 1000},       // metal visual
      {0.24, 80, 100, 0, 48000, 1.3e-5, 24000},    // wood actuator
      {0.48, 90, 300, 0, 48000, 7e-6, 24000},      // metal actuator
      {1.0, 0, 50, 0.3, 8000, 0, 8000},            // undamped with a phase
  };
  for (const Case& c : cases) {
    const auto y = synth(c.a, c.b, c.f, c.phi, c.rate, c.t0, c.n);
    const DampedSineFit fit = fit_damped_sine(y, c.rate, c.t0);
    ASSERT_TRUE(fit.ok);
    EXPECT_NEAR(fit.amplitude, c.a, 1e-6 * c.a);
    EXPECT_NEAR(fit.decay_per_s, c.b, 1e-6 * std::max(c.b, 1.0));
    EXPECT_NEAR(fit.freq_hz, c.f, 1e-6 * c.f);
    EXPECT_NEAR(fit.phase_rad, c.phi, 1e-6);
  }
}

TEST(DampedSineFit, StaysWithinOnePercentUnderNoise) {
  const auto y = synth(0.5, 80, 100, 0, 48000, 0, 9600, 0.005);  // SNR 40 dB at the start
  const DampedSineFit fit = fit_damped_sine(y, 48000, 0);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.decay_per_s, 80, 0.8);
  EXPECT_NEAR(fit.freq_hz, 100, 1.0);
}

TEST(DampedSineFit, RefusesWhatCannotBeFitted) {
  EXPECT_FALSE(fit_damped_sine(std::vector<double>(100, 0.0), 1000).ok);
  EXPECT_FALSE(fit_damped_sine(std::vector<double>{1, 2, 3}, 1000).ok);
  EXPECT_FALSE(fit_damped_sine(synth(1, 0, 1, 0, 1000, 0, 100), 1000).ok);  // a tenth of a cycle
}

}  // namespace
}  // namespace mallet
