// The kiosk stream's recording (audio/stream_capture.hpp) and the display's latency read from a
// photodiode in it (audio/photodiode_timing.hpp), against a simulated stream whose callbacks
// run late by known amounts and a screen whose light comes a known time after each present.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "audio/photodiode_timing.hpp"
#include "audio/stream_capture.hpp"

namespace mallet::audio {
namespace {

constexpr int kRate = 48000;
constexpr int kBlock = 256;
constexpr Nanos kStart = 5'000'000'000;  // the first block's due time, kiosk clock

// A stream of `seconds` whose block b is due at kStart + b·block/rate and whose callback
// runs `late(b)` after that; its input channel 0 is `light(t)` at the time each sample
// reached the input (the block's due time less `input_latency` plus its place).
// `split`: PortAudio hands each host buffer over in that many blocks, all called at once.
// `jump_at`: from that block on, the host's buffers come `jump` later than their frames say
// (a host that skipped time without skipping frames).
struct Host {
  int split = 1;
  std::size_t jump_at = 0;
  Nanos jump = 0;
  std::vector<std::size_t> xruns;  //!< the blocks the stream flags as over- or underflowing
  //! The share of the blocks after a buffer's first held up by `held` (drawn, seeded): in
  //! place of the regular hold-up of one block in seven.
  double held_share = -1;
  Nanos held = 0;
};

template <typename Light, typename Late>
CaptureRecording simulate(double seconds, Nanos input_latency, Light light, Late late, std::int64_t position0 = 777,
                          std::size_t skip_block = 0, Host host = {}) {
  StreamCapture cap(kRate, {1, 0}, seconds);
  cap.arm();
  std::vector<float> in(2 * kBlock);
  std::int64_t pos = position0;
  Nanos called = 0;
  std::mt19937 draw(7);
  std::bernoulli_distribution held_up(std::max(host.held_share, 0.0));
  for (std::size_t b = 0; !cap.complete(); ++b) {
    const Nanos shift = host.jump_at && b >= host.jump_at ? host.jump : 0;
    const Nanos due = kStart + shift + static_cast<Nanos>(std::llround(static_cast<double>(b) * kBlock * 1e9 / kRate));
    for (int i = 0; i < kBlock; ++i) {
      const Nanos t = due - input_latency + static_cast<Nanos>(std::llround(i * 1e9 / kRate));
      in[2 * i] = static_cast<float>(light(t));
      in[2 * i + 1] = -1.0f;  // channel 1: kept first by the capture
    }
    if (skip_block && b == skip_block) pos += kBlock;  // a block the stream never delivered
    // The first block of a host buffer is called when the buffer is due (and late); the others
    // of that buffer right after it.
    if (b % static_cast<std::size_t>(host.split) == 0) called = due + late(b);
    else if (host.held_share >= 0) called += held_up(draw) ? host.held : 20'000;
    else called += b % 7 == 3 ? 4'000'000 : 20'000;  // now and then held up (a busy machine)
    cap.write(in.data(), 2, kBlock, pos, called, std::find(host.xruns.begin(), host.xruns.end(), b) != host.xruns.end());
    pos += kBlock;
  }
  return cap.recording();
}

TEST(StreamCapture, KeepsTheChosenChannelsInOrderAndStampsEachBlock) {
  StreamCapture cap(kRate, {2, 0}, 0.01);  // 480 frames
  std::vector<float> in(3 * 100);
  for (int i = 0; i < 100; ++i) in[3 * i] = static_cast<float>(i), in[3 * i + 2] = static_cast<float>(-i);
  cap.write(in.data(), 3, 100, 0, 1, false);  // before arm: not kept
  EXPECT_FALSE(cap.armed());
  cap.arm();
  for (int b = 0; b < 5; ++b) cap.write(in.data(), 3, 100, 1000 + 100 * b, 10 + b, b == 3);
  ASSERT_TRUE(cap.complete());
  const CaptureRecording r = cap.recording();
  ASSERT_EQ(r.channels.size(), 2u);
  ASSERT_EQ(r.channels[0].size(), 480u);
  EXPECT_EQ(r.channels[0][7], -7.0f);  // input channel 2 first
  EXPECT_EQ(r.channels[1][107], 7.0f);
  ASSERT_EQ(r.blocks.size(), 5u);
  EXPECT_EQ(r.blocks[4].index, 400u);
  EXPECT_EQ(r.blocks[4].position, 1400);
  EXPECT_EQ(r.blocks[4].callback_ns, 14);
  EXPECT_EQ(r.xruns, 1u);
  EXPECT_TRUE(r.continuous);
  cap.write(in.data(), 3, 100, 1500, 15, false);  // complete: nothing more is kept
  EXPECT_EQ(cap.recording().blocks.size(), 5u);
}

TEST(StreamCapture, ABlockThatSkipsTheEnginesFramesBreaksIt) {
  StreamCapture cap(kRate, {0}, 0.01);
  std::vector<float> in(300);
  cap.arm();
  cap.write(in.data(), 1, 100, 0, 0, false);
  cap.write(in.data(), 1, 100, 300, 0, false);  // 200 frames went elsewhere
  cap.write(in.data(), 1, 300, 400, 0, false);
  EXPECT_FALSE(cap.recording().continuous);
  cap.arm();  // a new recording forgets it
  for (int b = 0; b < 5; ++b) cap.write(in.data(), 1, 100, 100 * b, 0, false);
  EXPECT_TRUE(cap.recording().continuous);
}

TEST(PhotodiodeTiming, TheCallbacksScheduleIsTheirEarliestAndLateOnesDoNotMoveIt) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<Nanos> jitter(0, 4'000'000);
  // Every 40th block's callback on time (a few in each half second), the others late.
  const CaptureRecording r = simulate(2.0, 0, [](Nanos) { return 0.0; },
                                      [&](std::size_t b) { return b % 40 == 0 ? Nanos{0} : jitter(rng) + 50'000; });
  EXPECT_EQ(capture_time(r, 0), kStart);
  EXPECT_EQ(capture_time(r, 48000), kStart + 1'000'000'000);
  EXPECT_NEAR(static_cast<double>(capture_time(r, 48000.5) - kStart), 1'000'010'416.7, 1);
}

// Squares presented at known times, their light `latency` later, lit for 100 ms.
struct Screen {
  std::vector<PhotodiodeSquare> squares;
  Nanos latency = 0;
  double on = 0.4, off = 0.05;
  double operator()(Nanos t) const {
    for (const PhotodiodeSquare& s : squares)
      if (s.present && t >= s.present + latency && t < s.present + latency + 100'000'000) return on;
    return off;
  }
};

Screen ten_squares(Nanos latency) {
  Screen s;
  s.latency = latency;
  for (int i = 0; i < 10; ++i) {
    const Nanos instant = kStart + 1'000'000'000 + i * 1'000'000'000LL;
    s.squares.push_back({instant, instant + 3'000'000 + (i % 3) * 16'666'667});  // the next frames' presents
  }
  return s;
}

TEST(PhotodiodeTiming, FindsEachSquaresLightAfterItsPresentToWithinASample) {
  const Nanos input_latency = 21'333'333;
  for (const Nanos latency : {Nanos{0}, Nanos{12'345'678}, Nanos{61'000'000}}) {
    const Screen screen = ten_squares(latency);
    std::mt19937 rng(11);
    std::uniform_int_distribution<Nanos> jitter(0, 3'000'000);
    const CaptureRecording r =
        simulate(12.0, input_latency, screen, [&](std::size_t b) { return b % 50 == 0 ? Nanos{20'000} : jitter(rng); });
    const PhotodiodeTiming t = time_photodiode(r, 1, input_latency * 1e-9, screen.squares, "photodiode");
    EXPECT_EQ(t.seen, 10);
    for (const PhotodiodePulse& p : t.pulses) {
      ASSERT_TRUE(p.latency_ms);
      EXPECT_NEAR(*p.latency_ms, static_cast<double>(latency) / 1e6, 1000.0 / kRate + 0.021) << "latency " << latency;
    }
    EXPECT_NEAR(t.display_latency_ms, static_cast<double>(latency) / 1e6, 1000.0 / kRate + 0.021);
    EXPECT_LE(t.min_ms, t.display_latency_ms);
    EXPECT_GE(t.max_ms, t.display_latency_ms);
  }
}

TEST(PhotodiodeTiming, AHostBufferHandedOverInSeveralBlocksAtOnceIsTimedByItsFirst) {
  // A JACK period of 1024 frames given to the kiosk's callback in four blocks of 256 (found on
  // the bench: timed by the last block, every light came most of a period early).
  const Screen screen = ten_squares(25'000'000);
  Host host;
  host.split = 4;
  const CaptureRecording r = simulate(12.0, 0, screen, [](std::size_t) { return Nanos{30'000}; }, 0, 0, host);
  const PhotodiodeTiming t = time_photodiode(r, 1, 0, screen.squares, "photodiode");
  EXPECT_EQ(t.seen, 10);
  EXPECT_NEAR(t.display_latency_ms, 25.0, 1000.0 / kRate + 0.031);
  EXPECT_NEAR(t.max_ms, 25.0, 1000.0 / kRate + 0.031);
}

TEST(PhotodiodeTiming, AHostBufferWhoseLaterBlocksOftenPauseIsStillTimedByItsFirst) {
  // The bench's sanitizer build: two blocks in five after a period's first held up, each by
  // more than half a block, so a pause between blocks one apart is commoner than a period
  // apart (timed by its blocks, every light came most of a period early).
  const Screen screen = ten_squares(25'000'000);
  Host host;
  host.split = 4;
  host.held_share = 0.4;
  host.held = 3'000'000;  // a block of 256 is 5.3 ms
  const CaptureRecording r = simulate(12.0, 0, screen, [](std::size_t) { return Nanos{30'000}; }, 0, 0, host);
  const PhotodiodeTiming t = time_photodiode(r, 1, 0, screen.squares, "photodiode");
  EXPECT_EQ(t.seen, 10);
  EXPECT_NEAR(t.display_latency_ms, 25.0, 1000.0 / kRate + 0.031);
  EXPECT_NEAR(t.min_ms, 25.0, 1000.0 / kRate + 0.031);
}

TEST(PhotodiodeTiming, AHostThatSkippedTimeIsTimedByItsCallbacksAfterTheSkip) {
  // Five seconds in, the host's buffers come a period later than their frames say.
  const Screen screen = ten_squares(25'000'000);
  Host host;
  host.jump_at = 5 * kRate / kBlock;
  host.jump = 21'333'333;
  const auto light = [&](Nanos t) { return screen(t); };
  const CaptureRecording r = simulate(12.0, 0, light, [](std::size_t) { return Nanos{10'000}; }, 0, 0, host);
  const PhotodiodeTiming t = time_photodiode(r, 1, 0, screen.squares, "photodiode");
  EXPECT_EQ(t.seen, 10);
  for (const PhotodiodePulse& p : t.pulses) EXPECT_NEAR(*p.latency_ms, 25.0, 1000.0 / kRate + 0.021);
}

TEST(PhotodiodeTiming, ReadsAPhotodiodeWiredTheOtherWayRoundAndOnlyTheSquaresShown) {
  Screen screen = ten_squares(30'000'000);
  screen.on = -0.3;  // a falling swing
  screen.off = 0.1;
  screen.squares[4].present = 0;  // never shown (a frame missed its instant and the next came late)
  const CaptureRecording r = simulate(12.0, 0, screen, [](std::size_t) { return Nanos{10'000}; });
  const PhotodiodeTiming t = time_photodiode(r, 1, 0, screen.squares, "photodiode");
  EXPECT_EQ(t.seen, 9);
  EXPECT_FALSE(t.pulses[4].light);
  EXPECT_NEAR(t.display_latency_ms, 30.0, 1000.0 / kRate + 0.011);
}

TEST(PhotodiodeTiming, APhotodiodeThatSeesNothingIsOneLineNamingItsChannel) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.01);
  const Screen screen = ten_squares(20'000'000);
  const CaptureRecording r = simulate(12.0, 0, [&](Nanos) { return noise(rng); }, [](std::size_t) { return Nanos{0}; });
  try {
    time_photodiode(r, 1, 0, screen.squares, "photodiode (input channel 3)");
    FAIL() << "no light, and no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("photodiode (input channel 3): the light was seen at 0 of 10 squares", 0), 0u)
        << e.what();
  }
}

TEST(PhotodiodeTiming, ASquareNearAnOverrunIsLeftOutAndTooManyLeftOutIsSaid) {
  const Screen screen = ten_squares(20'000'000);
  const auto at_second = [](double s) { return static_cast<std::size_t>((1.0 + s) * kRate / kBlock); };
  Host host;
  host.xruns = {at_second(2.05), at_second(6.2)};  // during the third square's light, and the seventh's
  const CaptureRecording r = simulate(12.0, 0, screen, [](std::size_t) { return Nanos{0}; }, 0, 0, host);
  EXPECT_EQ(r.xruns, 2u);
  const PhotodiodeTiming t = time_photodiode(r, 1, 0, screen.squares, "photodiode");
  EXPECT_EQ(t.seen, 8);
  EXPECT_EQ(t.near_xruns, 2);
  EXPECT_FALSE(t.pulses[2].light);
  EXPECT_FALSE(t.pulses[6].light);
  EXPECT_NEAR(t.display_latency_ms, 20.0, 1000.0 / kRate + 0.011);
  for (double s = 0; s < 10; s += 1.0) host.xruns.push_back(at_second(s + 0.1));  // every square's
  const CaptureRecording busy = simulate(12.0, 0, screen, [](std::size_t) { return Nanos{0}; }, 0, 0, host);
  try {
    time_photodiode(busy, 1, 0, screen.squares, "photodiode");
    FAIL() << "no square usable, and no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("seen at 0 of 10 squares (10 left out: the stream over- or underran"),
              std::string::npos)
        << e.what();
  }
}

TEST(PhotodiodeTiming, ARecordingWithAGapIsRefused) {
  const Screen screen = ten_squares(20'000'000);
  const CaptureRecording r = simulate(12.0, 0, screen, [](std::size_t) { return Nanos{0}; }, 0, 300);
  EXPECT_FALSE(r.continuous);
  EXPECT_THROW(time_photodiode(r, 1, 0, screen.squares, "photodiode"), std::runtime_error);
}

}  // namespace
}  // namespace mallet::audio
