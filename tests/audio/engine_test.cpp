// The real-time engine, without a device: sample-accurate starts inside blocks, both
// channels on the same sample, the actuator channel equal to the exact reference,
// scheduling modes, voice stealing, no allocation in the callback, and no volume or gain
// that drives a channel to full scale.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "audio/engine.hpp"
#include "core/config/instruments_config.hpp"
#include "core/named.hpp"
#include "core/operator_knobs.hpp"
#include "core/soft_clip.hpp"
#include "test_paths.hpp"

// Counts heap allocations made while `g_counting` is set (i.e. inside process()).
// The replaced global operator new/delete pair is malloc/free on purpose; GCC cannot see
// that they match once inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
std::atomic<bool> g_counting{false};
std::atomic<std::uint64_t> g_allocations{0};
}  // namespace

namespace {
void* counted_malloc(std::size_t size) noexcept {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size ? size : 1);
}
}  // namespace

// Every unaligned form is replaced, so that no allocation made through one of ours is
// released through the sanitizer's own (the standard library's stable_sort uses the
// nothrow form, for one).
void* operator new(std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace mallet::audio {
namespace {

using test::percussion;

std::vector<ModalPreset> simple_presets() {
  ModalPreset wood{"xylophone", {{1.0, 1.0, 10.0}, {3.0, 0.4, 30.0}}, 0.3, 2.0, 1.0};
  ModalPreset metal{"glockenspiel", {{1.0, 1.0, 2.0}, {2.756, 0.5, 6.0}, {5.404, 0.25, 12.0}}, 0.3, 2.0, 1.0};
  return {wood, metal};
}

using test::strike;

// Renders `frames` frames in blocks of `block`, posting each impact just before the
// block in which it falls (as a live input thread would, with no lateness).
std::vector<float> run(AudioEngine& engine, std::vector<Impact> impacts, std::int64_t frames, int block) {
  const int ch = engine.settings().routing.channels;
  const int fs = engine.settings().sample_rate_hz;
  std::vector<float> out(static_cast<std::size_t>(frames * ch));
  std::size_t next = 0;
  for (std::int64_t first = 0; first < frames; first += block) {
    const auto n = static_cast<int>(std::min<std::int64_t>(block, frames - first));
    const Nanos block_end_ns = (first + n) * kNanosPerSecond / fs;
    while (next < impacts.size() && impacts[next].t_ns < block_end_ns) engine.post(impacts[next++]);
    engine.process(out.data() + first * ch, n);
  }
  return out;
}

std::vector<double> channel(const std::vector<float>& interleaved, int channels, int c) {
  std::vector<double> out;
  for (std::size_t i = static_cast<std::size_t>(c); i < interleaved.size(); i += static_cast<std::size_t>(channels))
    out.push_back(interleaved[i]);
  return out;
}

std::int64_t first_nonzero(const std::vector<double>& x) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] != 0.0) return static_cast<std::int64_t>(i);
  return -1;
}

TEST(AudioEngine, ImpactInsideABlockStartsOnItsOwnSampleOnBothChannels) {
  for (int block : {16, 64, 256, 2048}) {
    AudioEngine engine(percussion(), simple_presets(), EngineSettings{});
    // 1.5 blocks of 64 in, plus 7 µs: between two samples.
    const Nanos t = 96 * kNanosPerSecond / 48000 + 7'000;
    const auto out = run(engine, {strike(3, t, 1.0)}, 4800, block);
    const auto acoustic = channel(out, 2, 0), actuator = channel(out, 2, 1);
    const std::int64_t own = (t * 48000 + kNanosPerSecond - 1) / kNanosPerSecond;  // first sample at or after t
    EXPECT_EQ(first_nonzero(actuator), own) << "block " << block;
    EXPECT_EQ(first_nonzero(acoustic), own) << "block " << block;
  }
}

TEST(AudioEngine, BothProducersRingsAreRenderedAlikeInOneCallback) {
  // The main thread (mouse, ghost) and the Wii Remote's reading thread each own a ring;
  // an impact sounds the same whichever ring brought it.
  const Nanos t = 96 * kNanosPerSecond / 48000 + 7'000;
  AudioEngine a(percussion(), simple_presets(), EngineSettings{});
  AudioEngine b(percussion(), simple_presets(), EngineSettings{});
  a.post(strike(3, t, 1.0), Producer::main);
  a.post(strike(12, t + 1'000'000, 0.5), Producer::main);
  b.post(strike(3, t, 1.0), Producer::input);
  b.post(strike(12, t + 1'000'000, 0.5), Producer::main);
  std::vector<float> out_a(2 * 4800), out_b(2 * 4800);
  a.process(out_a.data(), 4800);
  b.process(out_b.data(), 4800);
  EXPECT_EQ(out_a, out_b);
  EXPECT_EQ(b.counters().impacts, 2u);
  EXPECT_EQ(b.counters().dropped, 0u);
}

TEST(AudioEngine, ActuatorChannelEqualsExactEquationOneForAnyBlockSize) {
  std::vector<Impact> impacts;
  for (int k = 0; k < 30; ++k) impacts.push_back(strike(k % 16, 2'000'000 + k * 13'131'313, 0.3 + 0.05 * k));
  // The exact sum of Eq. 1 over the impacts, and how many voices are in their last
  // −100 dB (where the engine may already have retired them, by design).
  const double gain = ActuatorConfig{}.gain;
  std::vector<double> exact(48000, 0.0);
  std::vector<int> in_tail(48000, 0);
  for (const Impact& i : impacts) {
    const VibrationParams& p = percussion().materials[static_cast<std::size_t>(i.material)].actuator;
    for (std::size_t n = 0; n < exact.size(); ++n) {
      const long double t = static_cast<long double>(n) / 48000 - static_cast<long double>(i.t_ns) * 1e-9L;
      if (t < 0) continue;
      const long double env = gain * p.amplitude * i.speed_m_per_s * std::exp(-p.decay_per_s * t);
      exact[n] += static_cast<double>(env * std::sin(2 * std::numbers::pi_v<long double> * p.freq_hz * t));
      in_tail[n] += env < 2e-5L;
    }
  }
  for (int block : {16, 64, 1000, 2048}) {
    AudioEngine engine(percussion(), simple_presets(), EngineSettings{});
    const auto actuator = channel(run(engine, impacts, 48000, block), 2, 1);
    for (std::size_t n = 0; n < exact.size(); ++n)
      ASSERT_NEAR(actuator[n], exact[n], 1e-6 + 1e-5 * in_tail[n]) << "block " << block << " sample " << n;
  }
}

TEST(AudioEngine, TheActuatorInverseFiltersTheActuatorChannelAndTheNoteWaitsForItsLatency) {
  // A small inverse: its taps are what an impulse on the actuator channel gives back.
  EngineSettings plain;
  EngineSettings equalised;
  equalised.actuator_eq = {0.5, 0.0, 0.0, -0.2, 0.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.03};
  equalised.eq_alignment_samples = 3;
  const std::vector<Impact> impacts = {strike(3, 1'000'007, 1.0), strike(12, 9'333'333, 0.6)};
  for (int block : {16, 64, 1000}) {
    AudioEngine a(percussion(), simple_presets(), plain);
    AudioEngine b(percussion(), simple_presets(), equalised);
    const auto out_a = run(a, impacts, 4800, block), out_b = run(b, impacts, 4800, block);
    const auto act_a = channel(out_a, 2, 1), act_b = channel(out_b, 2, 1);
    const auto note_a = channel(out_a, 2, 0), note_b = channel(out_b, 2, 0);
    for (std::size_t n = 0; n < act_a.size(); ++n) {
      double want = 0;
      for (std::size_t j = 0; j < equalised.actuator_eq.size() && j <= n; ++j) want += equalised.actuator_eq[j] * act_a[n - j];
      ASSERT_NEAR(act_b[n], want, 1e-6) << "block " << block << " sample " << n;
      ASSERT_EQ(note_b[n], n < 3 ? 0.0f : static_cast<float>(note_a[n - 3])) << "block " << block << " sample " << n;
    }
  }
  // Frame 0 is heard 3 samples later than the device plays it.
  AudioEngine b(percussion(), simple_presets(), equalised);
  b.set_origin(1'000'000'000);
  EXPECT_EQ(b.origin(), 1'000'000'000 + 62'500);
  equalised.eq_alignment_samples = -1;
  EXPECT_THROW(AudioEngine(percussion(), simple_presets(), equalised), std::invalid_argument);
}

TEST(AudioEngine, AsSoonAsPossibleStartsALateImpactAtTheNextBlock) {
  AudioEngine engine(percussion(), simple_presets(), EngineSettings{});
  std::vector<float> out(2 * 64 * 4);
  engine.process(out.data(), 64);
  engine.process(out.data() + 128, 64);
  engine.post(strike(2, 10'000, 1.0));  // happened in block 0, known only now
  engine.process(out.data() + 256, 64);
  EXPECT_EQ(first_nonzero(channel(out, 2, 1)), 128 + 1);  // starts at phase 0 on sample 128
  EXPECT_EQ(engine.counters().late, 0u);  // no latency was promised
}

TEST(AudioEngine, ScheduleAheadGivesAConstantLatencyWithZeroJitter) {
  EngineSettings s;
  s.schedule_ahead_ms = 5.0;  // 240 samples
  for (int block : {32, 64, 128}) {
    for (Nanos t : {Nanos{1'000'007}, Nanos{1'333'333}, Nanos{2'020'202}}) {  // between samples
      AudioEngine engine(percussion(), simple_presets(), s);
      const auto actuator = channel(run(engine, {strike(9, t, 1.0)}, 2400, block), 2, 1);
      const std::int64_t want = ((t + 5'000'000) * 48000 + kNanosPerSecond - 1) / kNanosPerSecond;
      EXPECT_EQ(first_nonzero(actuator), want) << "block " << block << " t " << t;
      EXPECT_EQ(engine.counters().late, 0u);
    }
  }
}

TEST(AudioEngine, ThousandSimultaneousStrikesNeitherClipUncontrolledNorAllocate) {
  EngineSettings s;
  s.max_voices = 32;
  AudioEngine engine(percussion(), simple_presets(), s);
  for (int k = 0; k < 1000; ++k) engine.post(strike(k % 16, 1'000'000, 100.0));
  std::vector<float> out(2 * 256);
  g_allocations = 0;
  for (int b = 0; b < 200; ++b) {
    g_counting = true;
    engine.process(out.data(), 256);
    g_counting = false;
    for (float x : out) {
      ASSERT_TRUE(std::isfinite(x));
      ASSERT_LE(std::fabs(x), static_cast<float>(PeakLimiter::kCeiling));
    }
  }
  EXPECT_EQ(g_allocations.load(), 0u);
  const EngineCounters c = engine.counters();
  EXPECT_EQ(c.impacts, 1000u);
  EXPECT_EQ(c.dropped, 0u);
  EXPECT_EQ(c.stolen, 1000u - 32u);
  EXPECT_GT(c.clipped, 0u);
}

TEST(AudioEngine, VoicesRetireBelowMinusHundredDecibels) {
  AudioEngine engine(percussion(), simple_presets(), EngineSettings{});
  engine.post(strike(0, 0, 1.0));
  std::vector<float> out(2 * 4800);
  engine.process(out.data(), 4800);
  EXPECT_EQ(engine.counters().active_voices, 1);
  for (int i = 0; i < 30; ++i) engine.process(out.data(), 4800);  // 3 s: wood fundamental decays at 10/s
  EXPECT_EQ(engine.counters().active_voices, 0);
}

TEST(AudioEngine, MonoRoutingMixesBothSignalsIntoOneChannel) {
  EngineSettings stereo;
  EngineSettings mono;
  mono.routing = {1, 0, 0};
  AudioEngine a(percussion(), simple_presets(), stereo), b(percussion(), simple_presets(), mono);
  const std::vector<Impact> impacts{strike(10, 500'000, 0.8)};
  const auto s = run(a, impacts, 4800, 64);
  const auto m = run(b, impacts, 4800, 64);
  ASSERT_EQ(m.size() * 2, s.size());
  for (std::size_t i = 0; i < m.size(); ++i) ASSERT_NEAR(m[i], s[2 * i] + s[2 * i + 1], 1e-6) << i;
}

TEST(AudioEngine, RefusesSettingsItCannotHonourBeforeAnyAudioRuns) {
  EngineSettings bad_routing;
  bad_routing.routing = {2, 0, 2};
  EXPECT_THROW(AudioEngine(percussion(), simple_presets(), bad_routing), std::invalid_argument);
  EngineSettings low_rate;
  low_rate.sample_rate_hz = 500;  // metal's 300 Hz actuator is above Nyquist
  EXPECT_THROW(AudioEngine(percussion(), simple_presets(), low_rate), std::invalid_argument);
  EXPECT_THROW(AudioEngine(percussion(), {}, EngineSettings{}), std::invalid_argument);
}

// The shipped scene's own acoustic presets (config/instruments.toml), as audio_setup picks them.
std::vector<ModalPreset> shipped_scene_presets() {
  const std::vector<ModalPreset> library = config::load_instruments(percussion().instruments_file);
  std::vector<ModalPreset> presets;
  for (const Instrument& inst : percussion().instruments) presets.push_back(*find_named(library, inst.voice));
  return presets;
}

// A visitor playing for `seconds`: a strike every 150 ms over all the bars, fast and slow,
// with a chord of four now and then.
std::vector<Impact> busy_visitor(double seconds) {
  std::vector<Impact> impacts;
  const auto bars = static_cast<int>(percussion().targets.size());
  for (int k = 0; k * 0.15 < seconds; ++k) {
    const Nanos t = 1'000'000 + k * 150'000'000LL + (k * 7'919) % 20'833;  // off the sample grid
    impacts.push_back(strike((k * 5) % bars, t, 0.5 + 0.25 * (k % 11)));  // 0.5 .. 3 m/s
    if (k % 9 == 0)
      for (int j = 1; j < 4; ++j) impacts.push_back(strike((k + 3 * j) % bars, t, 3.0));
  }
  return impacts;
}

double peak(const std::vector<double>& x) {
  double p = 0;
  for (double v : x) p = std::max(p, std::fabs(v));
  return p;
}

TEST(AudioEngine, NoVolumeOrGainTheSettingsAllowDrivesEitherChannelToFullScale) {
  const std::vector<Impact> impacts = busy_visitor(1.0);
  // What full volume and gain would give without the limiter: the engine is linear below its
  // thresholds, so a quiet run scaled up is the unlimited signal. It must go past full scale,
  // or this test would prove nothing.
  EngineSettings quiet;
  quiet.acoustic_volume = 0.01;
  quiet.actuator.gain = 0.001;
  AudioEngine reference(percussion(), shipped_scene_presets(), quiet);
  const auto raw = run(reference, impacts, 48000, 256);
  ASSERT_LT(peak(channel(raw, 2, 0)), 0.9);
  ASSERT_LT(peak(channel(raw, 2, 1)), 0.9);
  EXPECT_GT(peak(channel(raw, 2, 0)) * kVolumeKnob.hi / quiet.acoustic_volume, 1.0);
  EXPECT_GT(peak(channel(raw, 2, 1)) * kGainKnob.hi / quiet.actuator.gain, 1.0);

  const float ceiling = static_cast<float>(PeakLimiter::kCeiling);
  for (double volume = 0.0; volume <= kVolumeKnob.hi + 1e-9; volume += 0.5) {
    for (double gain : {0.0, 1.0, kGainKnob.hi}) {
      EngineSettings s;
      s.acoustic_volume = volume;
      s.actuator.gain = gain;
      AudioEngine engine(percussion(), shipped_scene_presets(), s);
      const auto out = run(engine, impacts, 48000, 256);
      for (std::size_t i = 0; i < out.size(); ++i) {
        ASSERT_TRUE(std::isfinite(out[i]));
        ASSERT_LE(std::fabs(out[i]), ceiling) << "volume " << volume << " gain " << gain << " channel " << i % 2;
      }
    }
  }
  // The mono mix (one channel for both) at the top of both ranges.
  EngineSettings mono;
  mono.routing = {1, 0, 0};
  mono.acoustic_volume = kVolumeKnob.hi;
  mono.actuator.gain = kGainKnob.hi;
  AudioEngine engine(percussion(), shipped_scene_presets(), mono);
  for (float x : run(engine, impacts, 48000, 256)) ASSERT_LE(std::fabs(x), ceiling);
}

TEST(AudioEngine, AtVolumeFourTenSecondsOfPlayHaveNoSampleAtFullScale) {
  // The reported case (issue 29): [audio] volume = 4.0, 10 s of a visitor playing. The old
  // output stage (soft_clip to 1 per sample) gave full-scale samples here; the limiter none.
  const std::vector<Impact> impacts = busy_visitor(10.0);
  EngineSettings s;
  s.acoustic_volume = 4.0;
  AudioEngine engine(percussion(), shipped_scene_presets(), s);
  const auto out = run(engine, impacts, 10 * 48000, 512);
  EngineSettings unit;
  unit.acoustic_volume = 1.0 / 64;  // linear: below the threshold throughout
  AudioEngine reference(percussion(), shipped_scene_presets(), unit);
  const auto raw = channel(run(reference, impacts, 10 * 48000, 512), 2, 0);
  ASSERT_LT(peak(raw), 0.9);

  int full_scale_before = 0, full_scale_after = 0;
  for (double x : raw) full_scale_before += std::fabs(static_cast<float>(soft_clip(x * 64 * 4.0, 0.9))) >= 1.0f;
  for (std::size_t i = 0; i < out.size(); ++i) full_scale_after += std::fabs(out[i]) >= 1.0f;
  const double peak_after = peak(channel(out, 2, 0));
  std::printf("volume 4.0, 10 s: %d full-scale samples with the old soft clip, %d with the limiter; "
              "peak %.4f unlimited, %.4f limited\n",
              full_scale_before, full_scale_after, peak(raw) * 64 * 4.0, peak_after);
  EXPECT_GT(full_scale_before, 0);  // the case is reproduced, or the test proves nothing
  EXPECT_EQ(full_scale_after, 0);
  EXPECT_LE(peak_after, PeakLimiter::kCeiling);
  EXPECT_GT(engine.counters().clipped, 0u);
}

TEST(AudioEngine, ALoudSpeakerNeverTurnsTheActuatorDownNorDelaysEither) {
  // Each signal has its own limiter: at volume 4 the actuator channel is bit for bit what
  // it is at volume 0.1, and the first sample of each strike is where it was.
  const std::vector<Impact> impacts = busy_visitor(1.0);
  EngineSettings loud, soft;
  loud.acoustic_volume = kVolumeKnob.hi;
  soft.acoustic_volume = 0.1;
  AudioEngine a(percussion(), shipped_scene_presets(), loud), b(percussion(), shipped_scene_presets(), soft);
  const auto x = run(a, impacts, 48000, 128), y = run(b, impacts, 48000, 128);
  EXPECT_GT(a.counters().clipped, 0u);  // the speaker was limited
  EXPECT_EQ(channel(x, 2, 1), channel(y, 2, 1));
  EXPECT_EQ(first_nonzero(channel(x, 2, 0)), first_nonzero(channel(y, 2, 0)));
  const Nanos t = 96 * kNanosPerSecond / 48000 + 7'000;
  AudioEngine c(percussion(), shipped_scene_presets(), loud);
  const auto one = run(c, {strike(3, t, 3.0)}, 4800, 64);
  const std::int64_t own = (t * 48000 + kNanosPerSecond - 1) / kNanosPerSecond;
  EXPECT_EQ(first_nonzero(channel(one, 2, 0)), own);
  EXPECT_EQ(first_nonzero(channel(one, 2, 1)), own);
}

}  // namespace
}  // namespace mallet::audio
