// The native rate as the operator page shows it: samples stamped in the last second, counted
// on the samples' own (recorded) times.
#include "input/evdev/rate_meter.hpp"

#include <gtest/gtest.h>

namespace mallet::input::evdev {
namespace {

constexpr Nanos kMs = 1'000'000;

TEST(RateMeter, CountsTheSamplesOfTheLastSecond) {
  RateMeter meter;
  EXPECT_EQ(meter.rate_hz(0), 0.0);
  const Nanos t0 = 86'400 * kNanosPerSecond;
  for (int i = 0; i < 2000; ++i) meter.add(t0 + i * kMs);  // 1000 Hz for 2 s
  EXPECT_EQ(meter.rate_hz(t0 + 1999 * kMs), 1000.0);
  for (int i = 0; i < 125; ++i) meter.add(t0 + 2000 * kMs + i * 8 * kMs);  // then 125 Hz for 1 s
  EXPECT_EQ(meter.rate_hz(t0 + 2999 * kMs), 125.0);
  EXPECT_EQ(meter.rate_hz(t0 + 10 * kNanosPerSecond), 0.0);  // at rest
  meter.add(t0 + 11 * kNanosPerSecond);
  EXPECT_EQ(meter.rate_hz(t0 + 11 * kNanosPerSecond), 1.0);
  meter.clear();
  EXPECT_EQ(meter.rate_hz(t0 + 11 * kNanosPerSecond), 0.0);
}

TEST(RateMeter, SaturatesAtItsCapacity) {
  RateMeter meter(100);
  for (int i = 0; i < 1000; ++i) meter.add(i * kMs);
  EXPECT_EQ(meter.rate_hz(999 * kMs), 100.0);
}

}  // namespace
}  // namespace mallet::input::evdev
