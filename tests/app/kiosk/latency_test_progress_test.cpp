// The operator page's latency test (T) says where it is: each pulse as it comes, then done.
#include <gtest/gtest.h>

#include "app/kiosk/latency_test.hpp"
#include "audio/audio_setup.hpp"
#include "core/app_config.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

TEST(LatencyTestProgress, SaysEachPulseThenDoneThenNothing) {
  AppConfig config;
  audio::AudioRig rig = audio::make_audio_rig(test::percussion(), config, 48000);
  LatencyTest test;
  const Nanos start = 5 * kNanosPerSecond;
  EXPECT_EQ(test.status(start), "") << "no test yet";
  test.start(start, test::percussion(), *rig.engine);
  EXPECT_EQ(test.status(start), "latency test: the first pulse in 1 s");
  EXPECT_EQ(test.status(start + 600'000'000), "latency test: the first pulse in 1 s") << "never in 0 s";
  EXPECT_TRUE(test.pulsing(start));
  EXPECT_EQ(test.status(start + kNanosPerSecond), "latency test: pulse 1 of 10");
  EXPECT_EQ(test.status(start + 3 * kNanosPerSecond + 1), "latency test: pulse 3 of 10");
  EXPECT_EQ(test.status(start + 10 * kNanosPerSecond), "latency test: done");
  EXPECT_EQ(test.status(start + 10 * kNanosPerSecond + LatencyTest::kDoneShownFor - 1), "latency test: done");
  EXPECT_EQ(test.status(start + 10 * kNanosPerSecond + LatencyTest::kDoneShownFor), "");
  EXPECT_TRUE(test.pulsing(start + 10 * kNanosPerSecond + LatencyTest::kShown - 1)) << "the last square shows";
  EXPECT_FALSE(test.pulsing(start + 10 * kNanosPerSecond + LatencyTest::kShown));
}

}  // namespace
}  // namespace mallet::app
