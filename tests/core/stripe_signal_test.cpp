// Vibrotactile stripes (Eq. 1 of the second paper): frequency v/λ, phase continuity across
// blocks and speed changes, silence at rest and off the disc, an hour without drift.
#include "core/stripe_signal.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace mallet {
namespace {

constexpr int kRate = 48000;

StripeParams params() {
  StripeParams p;
  p.amplitude = 0.5;
  p.wavelength_m = 0.002;
  p.phase_rad = 0.3;
  p.fade_s = 0.005;
  p.motion_timeout_s = 10.0;  // the tests send no samples for long stretches
  return p;
}

std::vector<double> render(StripeSignal& s, int frames, int block) {
  std::vector<double> out(static_cast<std::size_t>(frames), 0.0);
  for (int i = 0; i < frames; i += block) s.add_to(out.data() + i, std::min(block, frames - i), 1.0);
  return out;
}

//! Frequency from upward zero crossings, interpolated, over the steady part.
double measured_frequency(const std::vector<double>& y, int skip) {
  double first = -1, last = -1;
  int crossings = 0;
  for (std::size_t i = static_cast<std::size_t>(skip) + 1; i < y.size(); ++i) {
    if (y[i - 1] < 0 && y[i] >= 0) {
      const double t = (static_cast<double>(i) - 1 + y[i - 1] / (y[i - 1] - y[i])) / kRate;
      if (first < 0) first = t;
      else ++crossings;
      last = t;
    }
  }
  return crossings / (last - first);
}

TEST(StripeSignal, FrequencyIsSpeedOverWavelength) {
  for (double v : {0.01, 0.05, 0.1, 0.3, 1.0}) {
    StripeSignal s(params(), kRate);
    s.motion(v, true);
    const std::vector<double> y = render(s, kRate, 256);
    const double f = measured_frequency(y, kRate / 100);
    EXPECT_NEAR(f, v / 0.002, 0.005 * v / 0.002) << "v = " << v;
  }
}

TEST(StripeSignal, PhaseIsContinuousAcrossBlocksAndSpeedChanges) {
  StripeSignal a(params(), kRate), b(params(), kRate);
  a.motion(0.1, true);
  b.motion(0.1, true);
  const std::vector<double> ya = render(a, 4800, 4800), yb = render(b, 4800, 7);  // blocks don't matter
  for (std::size_t i = 0; i < ya.size(); ++i) ASSERT_EQ(ya[i], yb[i]);

  // At a speed change the phase goes on from where it was: no step larger than the
  // faster speed's largest sample-to-sample change.
  StripeSignal s(params(), kRate);
  s.motion(0.1, true);
  std::vector<double> y = render(s, 2400, 64);
  for (double v : {0.3, 0.02, 0.2}) {
    s.motion(v, true);
    const std::vector<double> more = render(s, 2400, 64);
    y.insert(y.end(), more.begin(), more.end());
  }
  const double max_step = 0.5 * 2 * std::numbers::pi * (0.3 / 0.002) / kRate;  // A·2πf/fs
  for (std::size_t i = 480; i < y.size(); ++i) ASSERT_LE(std::fabs(y[i] - y[i - 1]), max_step * 1.01) << i;
}

TEST(StripeSignal, SilentAtRestAndOffTheDisc) {
  StripeSignal s(params(), kRate);
  std::vector<double> y = render(s, 4800, 64);
  for (double v : y) ASSERT_EQ(v, 0.0);  // nothing before any motion
  s.motion(0.1, true);
  y = render(s, 4800, 64);
  double peak = 0;
  for (double v : y) peak = std::max(peak, std::fabs(v));
  EXPECT_NEAR(peak, 0.5, 0.01);
  s.motion(0.0, true);  // stops on the disc
  y = render(s, 4800, 64);
  for (std::size_t i = 240; i < y.size(); ++i) ASSERT_EQ(y[i], 0.0) << i;  // after the 5 ms fade: exactly 0
  s.motion(0.1, false);  // moves off the disc
  y = render(s, 4800, 64);
  for (std::size_t i = 240; i < y.size(); ++i) ASSERT_EQ(y[i], 0.0) << i;
}

TEST(StripeSignal, AStoppedPointerFallsSilentAfterTheTimeout) {
  StripeParams p = params();
  p.motion_timeout_s = 0.05;
  StripeSignal s(p, kRate);
  s.motion(0.1, true);  // then nothing: the mouse stopped and sends no more samples
  const std::vector<double> y = render(s, kRate, 64);
  for (std::size_t i = 2400 + 240 + 1; i < y.size(); ++i) ASSERT_EQ(y[i], 0.0) << i;
  EXPECT_NE(y[1000], 0.0);
}

TEST(StripeSignal, AGestureStartsFromTheConfiguredPhase) {
  StripeSignal s(params(), kRate);
  s.motion(0.1, true);
  EXPECT_NEAR(s.current_phase(), 0.3, 1e-12);
  render(s, 1000, 64);
  s.motion(0.0, true);
  render(s, 4800, 64);  // silent: the gesture is over
  s.motion(0.1, true);
  EXPECT_NEAR(s.current_phase(), 0.3, 1e-12);
}

TEST(StripeSignal, StableOverAnHourOfMotion) {
  // An hour at a speed that changes at 1 kHz, against the phase summed in long double.
  StripePhase phase(params());
  long double reference = 0;
  double v = 0;
  const double dt = 1e-3;
  for (long k = 0; k < 3'600'000; ++k) {
    const double next_v = 0.1 + 0.05 * std::sin(static_cast<double>(k) * 1e-4);
    phase.update(dt, next_v);
    reference += static_cast<long double>(v) * dt;
    v = next_v;
  }
  const long double cycles = reference / 0.002L;
  double expected = static_cast<double>(2 * std::numbers::pi_v<long double> * (cycles - std::floor(cycles))) + 0.3;
  expected = std::fmod(expected, 2 * std::numbers::pi);
  double err = std::fabs(phase.phase_at(0) - expected);
  err = std::min(err, 2 * std::numbers::pi - err);
  EXPECT_GT(reference, 300.0L);  // it did travel (≈ 360 m)
  EXPECT_LT(err, 1e-6) << "phase error after an hour (rad)";
}

}  // namespace
}  // namespace mallet
