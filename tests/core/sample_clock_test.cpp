// Impacts land on their own sample: the first sample at or after the impact time,
// computed with integers so that it holds at any uptime.
#include <gtest/gtest.h>

#include "core/sample_clock.hpp"

namespace mallet {
namespace {

TEST(SampleClock, ExactSampleInstantsLandOnThatSample) {
  EXPECT_EQ(align_to_sample(0, 48000).index, 0);
  EXPECT_EQ(align_to_sample(0, 48000).delay_s, 0.0);
  EXPECT_EQ(align_to_sample(kNanosPerSecond, 48000).index, 48000);
  EXPECT_EQ(align_to_sample(kNanosPerSecond / 8, 8000).index, 1000);
}

TEST(SampleClock, BetweenTwoSamplesStartsOnTheNextWithTheRemainder) {
  // 48 kHz: a sample every 20833.33 ns. 30000 ns lies between samples 1 and 2.
  const SampleAlignment a = align_to_sample(30'000, 48000);
  EXPECT_EQ(a.index, 2);
  EXPECT_NEAR(a.delay_s, 2.0 / 48000 - 30e-6, 1e-15);
  EXPECT_GE(a.delay_s, 0.0);
  EXPECT_LT(a.delay_s, 1.0 / 48000);
}

TEST(SampleClock, ThirtyDaysOfUptimeDoNotOverflowOrDrift) {
  const Nanos days30 = Nanos{30} * 86'400 * kNanosPerSecond;
  const SampleAlignment a = align_to_sample(days30 + 30'000, 48000);
  EXPECT_EQ(a.index, Nanos{30} * 86'400 * 48000 + 2);
  EXPECT_NEAR(a.delay_s, 2.0 / 48000 - 30e-6, 1e-15);
  EXPECT_DOUBLE_EQ(seconds_since(a, a.index + 48000, 48000), 1.0 + a.delay_s);
}

TEST(SampleClock, NegativeTimesUseFloorDivision) {
  const SampleAlignment a = align_to_sample(-30'000, 48000);
  EXPECT_EQ(a.index, -1);
  EXPECT_NEAR(a.delay_s, 30e-6 - 1.0 / 48000, 1e-15);
}

}  // namespace
}  // namespace mallet
