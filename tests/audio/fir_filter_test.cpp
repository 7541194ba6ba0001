// The callback's FIR filter (audio/fir_filter.hpp): the convolution sum, sample by sample.
#include <gtest/gtest.h>

#include <random>

#include "audio/fir_filter.hpp"

namespace mallet::audio {
namespace {

TEST(FirFilter, EachOutputIsTheConvolutionSumOfTheTapsAndThePastInputs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> taps(37), x(500);
  for (double& t : taps) t = u(rng);
  for (double& v : x) v = u(rng);
  FirFilter fir(taps);
  for (std::size_t n = 0; n < x.size(); ++n) {
    double expected = 0;
    for (std::size_t j = 0; j < taps.size() && j <= n; ++j) expected += taps[j] * x[n - j];
    ASSERT_NEAR(fir.tick(x[n]), expected, 1e-12) << "sample " << n;
  }
}

TEST(FirFilter, BlocksGiveTheSameSamplesAsOneAtATimeAndResetForgetsThePast) {
  std::vector<double> taps = {0.5, -0.25, 0.125, 1.0};
  std::vector<double> x = {1, 2, 3, -4, 5, 0, 0, 7, 1, 1, -1};
  FirFilter one(taps), blocks(taps);
  std::vector<double> y = x;
  blocks.process(y.data(), 4);
  blocks.process(y.data() + 4, static_cast<int>(y.size()) - 4);
  for (std::size_t n = 0; n < x.size(); ++n) EXPECT_DOUBLE_EQ(y[n], one.tick(x[n]));
  one.reset();
  EXPECT_DOUBLE_EQ(one.tick(1.0), 0.5);
  EXPECT_DOUBLE_EQ(one.tick(0.0), -0.25);
}

TEST(FirFilter, WithoutTapsItPassesItsInputThrough) {
  FirFilter none;
  EXPECT_FALSE(none.active());
  std::vector<double> x = {0.1, -0.7, 0.3};
  none.process(x.data(), 3);
  EXPECT_EQ(x, (std::vector<double>{0.1, -0.7, 0.3}));
  EXPECT_EQ(none.tick(0.25), 0.25);
}

TEST(FirFilter, AfterSilenceAsLongAsTheFilterTheOutputIsZeroAndTheNextSoundIsFilteredAsNew) {
  const std::vector<double> taps = {1.0, 0.5, 0.25};
  FirFilter fir(taps), fresh(taps);
  EXPECT_DOUBLE_EQ(fir.tick(2.0), 2.0);
  EXPECT_DOUBLE_EQ(fir.tick(0.0), 1.0);
  EXPECT_DOUBLE_EQ(fir.tick(0.0), 0.5);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(fir.tick(0.0), 0.0);
  for (double x : {0.3, -0.1, 0.0, 0.7}) EXPECT_DOUBLE_EQ(fir.tick(x), fresh.tick(x));
}

}  // namespace
}  // namespace mallet::audio
