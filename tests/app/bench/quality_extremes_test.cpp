// The extremes, swept across the three quality presets (core/quality.hpp): impact speeds
// 0…100 m/s, pointer rates 30–1000 Hz, B from 0 to 10⁴ s⁻¹, f from 0.1 Hz to above
// Nyquist, 30 days of uptime, blocks of 16–2048 frames, frame times 1–100 ms and a 2 s
// stall. Asserted: no NaN or inf, no denormal operand anywhere in the audio path (the
// x86 DE flag, with FTZ off), bounded outputs, the same strikes in every preset, and each
// preset's documented error bounds. No test here measures time.
#include <cfloat>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "audio/audio_setup.hpp"
#include "app/bench/exact_reference.hpp"
#include "core/strike_loop.hpp"
#include "audio/damped_oscillator.hpp"
#include "audio/denormals.hpp"
#include "audio/modal_bar.hpp"
#include "core/config/instruments_config.hpp"
#include "core/one_euro_filter.hpp"
#include "core/quality.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

constexpr Quality kPresets[] = {Quality::fast, Quality::balanced, Quality::exact};
using app::eq1_ld;
using app::NoteReference;

constexpr int kRate = 48000;

AppConfig preset(Quality q) {
  AppConfig c;
  apply_quality(q, c);
  return c;
}

bool normal_or_zero(double x) { return std::isfinite(x) && (x == 0.0 || std::fabs(x) >= DBL_MIN); }
bool normal_or_zero(float x) { return std::isfinite(x) && (x == 0.0f || std::fabs(x) >= FLT_MIN); }

//! The x86 "denormal operand" flag is sticky: cleared before, read after a run.
struct DenormalWatch {
  DenormalWatch() {
#ifdef MALLET_HAS_MXCSR
    _mm_setcsr(_mm_getcsr() & ~kDenormalFlag);
#endif
  }
  bool seen() const {
#ifdef MALLET_HAS_MXCSR
    return (_mm_getcsr() & kDenormalFlag) != 0;
#else
    return false;
#endif
  }
  static constexpr unsigned kDenormalFlag = 0x0002;
};

//! A straight descent onto bar `bar` at `v` m/s (30 mm follow-through, then still),
//! sampled at `rate_hz`, starting at `t0`.
std::vector<PointerSample> descent(const Scene& scene, int bar, double v, double rate_hz, Nanos t0) {
  const Target& b = scene.targets[static_cast<std::size_t>(bar)];
  const double x = 0.5 * (b.x_min + b.x_max);
  // Starts at most 0.1 s above the bar (5 mm at least: above the re-arm height), ends as far below (30 mm at most).
  const double travel_m = std::clamp(0.1 * v, 0.005, 0.03);
  const double y0 = b.top_y + scene.mallet_radius_m + travel_m;
  const double y_end = b.top_y + scene.mallet_radius_m - travel_m;
  std::vector<PointerSample> s;
  const double duration_s = 0.3 + (v > 0 ? std::min(2.5, 2 * travel_m / v) : 0.0);
  for (int k = 0; k <= static_cast<int>(duration_s * rate_hz); ++k) {
    const double t = k / rate_hz;
    s.push_back({t0 + static_cast<Nanos>(std::llround(t * 1e9)), x, std::max(y_end, y0 - v * t)});
  }
  return s;
}

struct Strike {
  Nanos t;
  int target;
  double v;
  friend bool operator==(const Strike&, const Strike&) = default;
};

//! Runs one preset's kiosk loop over the tracks: the strikes it finds, and its audio
//! rendered in the preset's blocks (checked for bounds and subnormals as it goes).
std::vector<Strike> run_preset(Quality q, const std::vector<std::vector<PointerSample>>& tracks, Nanos origin) {
  const Scene& scene = test::percussion();
  const AppConfig config = preset(q);
  StrikeLoop loop(scene, config);
  audio::AudioRig rig = audio::make_audio_rig(scene, config, kRate);
  rig.engine->set_origin(origin);
  const int block = config.audio.frames_per_buffer;
  std::vector<float> out(static_cast<std::size_t>(2 * block));
  std::vector<Strike> strikes;
  for (const auto& track : tracks) {
    loop.reset();
    for (const PointerSample& s : track) {
      if (const auto impact = loop.feed(s.t_ns, {s.x, s.y})) {
        strikes.push_back({impact->t_ns - origin, impact->target, impact->speed_m_per_s});
        EXPECT_TRUE(rig.engine->post(*impact));
      }
      const Vec2 shown = loop.displayed(s.t_ns + 16'666'667);
      EXPECT_TRUE(std::isfinite(shown.x) && std::isfinite(shown.y));
      EXPECT_LT(std::fabs(shown.y), 1.0);  // metres: A·v_max = 0.02 s · 10 m/s = 0.2 m at most
      // The audio clock follows the hand's clock.
      while (origin + static_cast<Nanos>(rig.engine->position()) * kNanosPerSecond / kRate < s.t_ns) {
        rig.engine->process(out.data(), block);
        for (float x : out) {
          EXPECT_TRUE(normal_or_zero(x)) << x;
          EXPECT_LE(std::fabs(x), 1.0f);
        }
      }
    }
  }
  return strikes;
}

TEST(QualityExtremes, ImpactSpeedsFromZeroToAHundredMetresPerSecondAtEveryPointerRate) {
  const Scene& scene = test::percussion();
  std::vector<std::vector<PointerSample>> tracks;
  int bar = 0;
  Nanos t = kNanosPerSecond;
  for (double rate : {30.0, 60.0, 100.0, 250.0, 1000.0})
    for (double v : {0.0, 0.001, 0.01, 0.5, 2.0, 10.0, 100.0}) {
      tracks.push_back(descent(scene, bar, v, rate, t));
      t = tracks.back().back().t_ns + kNanosPerSecond / 2;
      bar = (bar + 5) % static_cast<int>(scene.targets.size());
    }
  DenormalWatch watch;
  std::vector<std::vector<Strike>> per_preset;
  for (Quality q : kPresets) per_preset.push_back(run_preset(q, tracks, 0));
  EXPECT_FALSE(watch.seen()) << "a denormal operand reached the FPU (FTZ off)";
  // Quality never changes which strikes happen, and on these straight descents not when or
  // how hard either: fast and balanced predict them (exact waits for the samples), and a
  // constant-speed descent is extrapolated exactly, up to the rounding of the fit.
  ASSERT_FALSE(per_preset[0].empty());
  for (std::size_t p = 1; p < per_preset.size(); ++p) {
    ASSERT_EQ(per_preset[p].size(), per_preset[0].size()) << to_string(kPresets[p]);
    for (std::size_t i = 0; i < per_preset[0].size(); ++i) {
      const Strike& a = per_preset[0][i];
      const Strike& b = per_preset[p][i];
      EXPECT_EQ(b.target, a.target) << i;
      EXPECT_LE(std::llabs(b.t - a.t), 1000) << i;  // 1 µs
      EXPECT_NEAR(b.v, a.v, 1e-9 * a.v) << i;
    }
  }
  // Every descent at ≥ 0.01 m/s strikes once (5 rates × 5 speeds); slower ones only touch.
  EXPECT_EQ(per_preset[0].size(), 25u);
  for (const Strike& s : per_preset[0]) {
    EXPECT_GT(s.v, 0.0);
    EXPECT_LE(s.v, AppConfig{}.contact.max_impact_speed_m_per_s);  // 100 m/s is clamped
  }
}

TEST(QualityExtremes, ThirtyDaysOfUptimeFindTheSameStrikesAsTheFirstSecond) {
  const Scene& scene = test::percussion();
  for (Quality q : kPresets) {
    const Nanos boot = 30 * test::kDay + 123'456'789;
    const auto early = run_preset(q, {descent(scene, 4, 2.0, 100.0, kNanosPerSecond)}, 0);
    const auto late = run_preset(q, {descent(scene, 4, 2.0, 100.0, boot + kNanosPerSecond)}, boot);
    ASSERT_EQ(early.size(), 1u);
    ASSERT_EQ(late.size(), 1u);
    EXPECT_EQ(late[0].target, early[0].target);
    EXPECT_NEAR(static_cast<double>(late[0].t - early[0].t), 0.0, 2.0);  // ns
    EXPECT_NEAR(late[0].v, early[0].v, 1e-9);
  }
}

//! Eq. 1 in long double: the reference of the actuator channel.

TEST(QualityExtremes, OscillatorFromUndampedToTenThousandPerSecondAndPastNyquistStaysExact) {
  // The actuator's oscillator is the same in every preset: ≤ 1e-9 of Eq. 1 everywhere.
  DenormalWatch watch;
  for (double b : {0.0, 1.0, 80.0, 1000.0, 1e4})
    for (double f : {0.1, 100.0, 4000.0, 23999.0, 24000.0, 30000.0, 47999.0}) {
      audio::DampedOscillator osc;
      osc.start(1.0, b, f, 0.3 / kRate, kRate);
      double worst = 0;
      for (int n = 0; n < kRate; ++n) {  // one second
        const double x = osc.tick();
        ASSERT_TRUE(normal_or_zero(x)) << b << " " << f << " " << n;
        ASSERT_LE(std::fabs(x), 1.0 + 1e-12);
        const long double want = eq1_ld(1.0L, b, f, (n + 0.3L) / kRate);
        if (std::fabs(want) > 1e-250L) worst = std::max(worst, std::fabs(x - static_cast<double>(want)));
      }
      EXPECT_LE(worst, 1e-9) << "B " << b << " f " << f;
      EXPECT_TRUE(normal_or_zero(osc.envelope()));
    }
  EXPECT_FALSE(watch.seen());
  // The visual bounce at the same extremes: bounded by A·v, finite.
  for (double b : {0.0, 8.0, 1e4})
    for (double f : {0.1, 15.0, 30000.0})
      for (Nanos t = 0; t < 3 * kNanosPerSecond; t += 7'000'003) {
        const double q = eq1({0.02, b, f}, 100.0, t);
        ASSERT_TRUE(normal_or_zero(q));
        ASSERT_LE(std::fabs(q), 0.02 * 100.0);
      }
}


TEST(QualityExtremes, EachPresetsAcousticErrorIsWithinItsDocumentedBound) {
  const std::vector<ModalPreset> library = config::load_instruments(test::config_dir() / "instruments.toml");
  // The three presets, then the max_modes knob turned down to 3 by hand.
  std::vector<int> max_modes;
  for (Quality q : kPresets) max_modes.push_back(preset(q).audio.max_modes);
  max_modes.push_back(3);
  for (std::size_t c = 0; c < max_modes.size(); ++c) {
    double worst = 0, bound = 1e-9;
    for (ModalPreset p : library) {
      p.max_sounding_modes = max_modes[c];
      if (max_modes[c] < static_cast<int>(p.modes.size())) bound = kThreeModeNoteErrorBound;
      for (double v : {0.01, 1.0, 2.0, 10.0, 100.0})
        for (double f0 : {261.63, 4186.0}) {
          audio::ModalBarVoice voice;
          voice.strike(p, f0, v, 0.0, kRate);
          const NoteReference note(p, f0, v, kRate);
          for (int n = 0; n < kRate / 10; ++n) {
            const double x = voice.tick();
            ASSERT_TRUE(normal_or_zero(x));
            ASSERT_LT(std::fabs(x), 1.0);
            worst = std::max(worst, std::fabs(x - static_cast<double>(note(static_cast<long double>(n) / kRate))));
          }
        }
    }
    EXPECT_LE(worst, bound) << (c < 3 ? to_string(kPresets[c]) : "max_modes = 3");
  }
}

TEST(QualityExtremes, BlockSizesFromSixteenToTwoThousandFortyEightFrames) {
  const Scene& scene = test::percussion();
  for (Quality q : kPresets) {
    AppConfig config = preset(q);
    for (int block : {16, 17, 64, 128, 1000, 2048}) {
      audio::AudioRig rig = audio::make_audio_rig(scene, config, kRate);
      std::vector<float> out(static_cast<std::size_t>(2 * block));
      // A strike 0.3 ms into the stream, posted before the first block.
      const Nanos t = 300'000;
      rig.engine->post(test::strike(7, t, 3.0));
      std::int64_t first = -1;
      DenormalWatch watch;
      for (int b = 0; b * block < 3 * kRate; ++b) {
        const std::int64_t base = rig.engine->position();
        rig.engine->process(out.data(), block);
        for (int i = 0; i < block; ++i) {
          const float a = out[static_cast<std::size_t>(2 * i)], u = out[static_cast<std::size_t>(2 * i + 1)];
          ASSERT_TRUE(normal_or_zero(a) && normal_or_zero(u)) << block;
          ASSERT_LE(std::fabs(a), 1.0f);
          ASSERT_LE(std::fabs(u), 1.0f);
          if (first < 0 && u != 0.0f) first = base + i;
        }
      }
      EXPECT_FALSE(watch.seen()) << to_string(q) << " " << block;
      EXPECT_EQ(rig.engine->counters().active_voices, 0) << "retired within 3 s";
      // The strike's first sample: as scheduled, on the sample clock.
      const double t_s = static_cast<double>(t) * 1e-9 + config.audio.schedule_ahead_ms * 1e-3;
      const std::int64_t due = static_cast<std::int64_t>(std::ceil(t_s * kRate));
      ASSERT_GE(first, due) << to_string(q) << " " << block;
      if (config.audio.schedule_ahead_ms > 0 && block <= due)
        EXPECT_LE(first - due, 1) << "exact: the constant latency, ± one sample";
      else
        EXPECT_LE(first - due, block) << "as soon as possible: within one block";
      EXPECT_EQ(rig.engine->counters().late, 0u) << to_string(q) << " " << block;
    }
  }
}

TEST(QualityExtremes, FrameTimesFromOneToAHundredMillisecondsAndATwoSecondStall) {
  const Scene& scene = test::percussion();
  for (Quality q : kPresets) {
    const AppConfig config = preset(q);
    StrikeLoop loop(scene, config);
    OneEuroFilter filter(config.pointer);
    const auto track = descent(scene, 9, 4.0, 1000.0, 10 * test::kDay);
    for (const PointerSample& s : track) {
      loop.feed(s.t_ns, {s.x, s.y});
      filter.update(s.t_ns, {s.x, s.y});
    }
    Nanos now = track.back().t_ns;
    for (Nanos frame : {1'000'000LL, 16'666'667LL, 33'333'333LL, 100'000'000LL, 2'000'000'000LL, 1'000'000LL}) {
      for (int k = 0; k < 5; ++k) {
        now += frame;
        const Vec2 shown = loop.displayed(now);
        ASSERT_TRUE(std::isfinite(shown.x) && std::isfinite(shown.y));
        ASSERT_LT(std::fabs(shown.y - track.back().y), 0.2);
        const auto cursor = filter.update(now, {track.back().x, track.back().y});
        ASSERT_TRUE(cursor && std::isfinite(cursor->x) && std::isfinite(cursor->y));
      }
    }
    // After the stall the bounce has died away: the head rests on the bar.
    const Target& bar = scene.targets[9];
    EXPECT_NEAR(loop.displayed(now).y, bar.top_y + scene.mallet_radius_m, 1e-6) << to_string(q);
  }
}

TEST(QualityExtremes, FlushToZeroIsOnWhereTheAudioThreadAsksForIt) {
  {
    audio::ScopedFlushDenormals ftz;
#ifdef MALLET_HAS_MXCSR
    EXPECT_TRUE(audio::ScopedFlushDenormals::active());
    volatile double tiny = DBL_MIN;
    volatile double half = tiny / 4.0;  // would be subnormal: flushed
    EXPECT_EQ(half, 0.0);
#endif
  }
  EXPECT_FALSE(audio::ScopedFlushDenormals::active());
}

}  // namespace
}  // namespace mallet
