// The latency test's photodiode (app/kiosk/photodiode_latency.hpp): the squares' presents the
// test keeps, what the kiosk's stream is asked to record, and a photodiode the stream does not
// record said on the operator page. The timing itself: tests/audio/photodiode_timing_test.cpp;
// through a real stream, X server and JACK server: bench.actuator.
#include <gtest/gtest.h>

#include "app/kiosk/latency_test.hpp"
#include "app/kiosk/photodiode_latency.hpp"
#include "audio/audio_setup.hpp"
#include "core/app_config.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

TEST(PhotodiodeLatency, EachSquareKeepsThePresentOfTheFirstFrameThatShowedIt) {
  AppConfig config;
  audio::AudioRig rig = audio::make_audio_rig(test::percussion(), config, 48000);
  LatencyTest test;
  const Nanos start = 5 * kNanosPerSecond;
  test.start(start, test::percussion(), *rig.engine);
  ASSERT_EQ(test.squares().size(), static_cast<std::size_t>(LatencyTest::kPulses));
  const Nanos first = start + kNanosPerSecond;
  EXPECT_FALSE(test.square_shown(first - 1));
  EXPECT_TRUE(test.square_shown(first + 4'000'000));   // the first frame at or after it
  EXPECT_TRUE(test.square_shown(first + 20'666'667));  // the next: not the first
  EXPECT_EQ(test.squares()[0].instant, first);
  EXPECT_EQ(test.squares()[0].present, first + 4'000'000);
  EXPECT_EQ(test.squares()[1].present, 0) << "not shown yet";
  EXPECT_FALSE(test.finished(start + 10 * kNanosPerSecond));
  EXPECT_TRUE(test.finished(start + 10 * kNanosPerSecond + LatencyTest::kShown));
}

TEST(PhotodiodeLatency, TheStreamRecordsItsChannelForTheWholeTestOnlyWhenOneIsSet) {
  TimingConfig timing;
  EXPECT_FALSE(photodiode_capture(timing));
  timing.photodiode_channel = 3;
  timing.photodiode_input = "USB";
  const std::optional<audio::CaptureSpec> spec = photodiode_capture(timing);
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->input_device, "USB");
  EXPECT_EQ(spec->input_channels, std::vector<int>{2});
  EXPECT_GE(spec->seconds, LatencyTest::kPulses + 0.1 + 0.3) << "the last square and the light after it";
}

TEST(PhotodiodeLatency, AStreamThatDoesNotRecordItIsSaidOnThePageAndEscLeavesIt) {
  PhotodiodeLatency diode(2, "");
  EXPECT_TRUE(diode.page_lines(0).empty());
  diode.start(nullptr);
  ASSERT_EQ(diode.phase(), PhotodiodeLatency::Phase::failed);
  EXPECT_EQ(diode.problem().rfind("photodiode (input channel 2): the sound card's stream does not record it", 0), 0u)
      << diode.problem();
  const std::vector<PageLine> lines = diode.page_lines(0);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].tone, PageTone::warning);
  EXPECT_EQ(lines[0].text, diode.problem());
  EXPECT_NE(lines[1].text.find("Esc"), std::string::npos);
  diode.answered();
  EXPECT_EQ(diode.phase(), PhotodiodeLatency::Phase::idle);
  EXPECT_TRUE(diode.page_lines(0).empty());
}

}  // namespace
}  // namespace mallet::app
