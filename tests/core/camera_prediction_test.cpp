// Contact prediction tuned for a camera (core/camera_prediction.hpp): it changes only what
// it says and leaves prediction off off; at 120 and 240 Hz with the camera's read delay, a
// hand that stops at or above the clearance is never predicted (exact samples, and the
// camera corpus at the measured and at a pessimistic noise); through the strike route it
// adds no false and no missed strike to the solver's on a camera corpus; and on clean
// strikes its contact time and speed stay within the bounds stated here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera_prediction.hpp"
#include "core/strike_detector.hpp"
#include "core/stroke_corpus.hpp"
#include "core/stop_above_check.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

constexpr Nanos kCameraT0 = 40 * 86'400 * kNanosPerSecond;
constexpr double kRates[] = {120.0, 240.0};

//! The shipped presets tuned for the corpus's V4L2 camera at `camera`'s rate and noise.
std::vector<PredictionConfig> tuned_presets(const CameraModel& camera) {
  std::vector<PredictionConfig> out;
  for (const PredictionConfig& p : {prediction_balanced(), prediction_exact(), prediction_eager()})
    out.push_back(prediction_for_camera(p, camera, percussion()));
  return out;
}

TEST(CameraPrediction, ChangesOnlyWhatItSays) {
  const PredictionConfig off = prediction_for_camera(prediction_off(), 240, 2.5e-5, 4.42);
  EXPECT_EQ(off.horizon_ms, 0.0);
  EXPECT_EQ(off.sample_delay_ms, 0.0);
  const PredictionConfig b = prediction_balanced();
  const PredictionConfig t = prediction_for_camera(b, 240, 2.5e-5, 4.42);
  EXPECT_DOUBLE_EQ(t.fit_window_ms, kCameraFitWindowFrames * 1e3 / 240);
  EXPECT_EQ(t.noise_m, 2.5e-5);
  EXPECT_EQ(t.sample_delay_ms, 4.42);
  EXPECT_EQ(t.horizon_ms, b.horizon_ms);
  EXPECT_EQ(t.braking_m_per_s2, b.braking_m_per_s2);
  EXPECT_EQ(t.clearance_m, b.clearance_m);
  EXPECT_EQ(t.min_predicted_speed_m_per_s, b.min_predicted_speed_m_per_s);
  EXPECT_EQ(t.max_speedup_m_per_s2, b.max_speedup_m_per_s2);
  EXPECT_EQ(t.min_overshoot_m, b.min_overshoot_m);
  // At 120 Hz the next frame arrives after the horizon: no reach across the read-out, and
  // the preset's 35 ms window is already shorter than 4.5 frames. An unknown rate changes nothing.
  const PredictionConfig slow = prediction_for_camera(b, 120, 2.5e-5, 8.58);
  EXPECT_EQ(slow.sample_delay_ms, 0.0);
  EXPECT_EQ(slow.fit_window_ms, b.fit_window_ms);
  EXPECT_EQ(prediction_for_camera(b, 0, 2.5e-5, 4.42).fit_window_ms, b.fit_window_ms);
  EXPECT_EQ(prediction_for_camera(b, 0, 2.5e-5, 4.42).sample_delay_ms, 0.0);
}

TEST(CameraPrediction, ReadDelayIsHalfTheExposureAndOneFrame) {
  EXPECT_NEAR(v4l2_read_delay_ms(240, 500), 0.25 + 1e3 / 240, 1e-12);
  EXPECT_NEAR(v4l2_read_delay_ms(120, 500), 0.25 + 1e3 / 120, 1e-12);
  EXPECT_NEAR(v4l2_read_delay_ms(120, 0), 1.5e3 / 120, 1e-12);  // automatic: a whole frame
  EXPECT_EQ(v4l2_camera(240).read_delay_ms, v4l2_read_delay_ms(240, kV4l2ExposureUs));
  EXPECT_EQ(wii_camera(100).read_delay_ms, 0.0);
}

// The could_stop guarantee holds for the tuned presets, reaching to the next frame's
// arrival: a hand braking at no more than half of braking_m_per_s2 that stops clearance_m
// or more above a bar is never predicted, on exact samples, at any peak speed, stop height
// and phase.
TEST(CameraPrediction, NeverPredictsAHandThatStopsAboveTheClearance) {
  int strokes = 0;
  for (double rate : kRates)
    for (const PredictionConfig& config : tuned_presets(v4l2_camera(rate)))
      strokes += test::expect_stops_never_predicted(config, percussion(), 3, rate, kCameraT0);
  EXPECT_EQ(strokes, 2 * 3 * 5 * 5 * 4);
}

//! The V4L2 camera at both rates with σ `noise_px`.
CorpusConfig camera_corpus(std::uint32_t seed, int shapes, double noise_px) {
  CorpusConfig c;
  c.seed = seed;
  c.shapes_per_kind = shapes;
  c.cameras = {v4l2_camera(120.0), v4l2_camera(240.0)};
  for (CameraModel& m : c.cameras) m.noise_px = noise_px;
  return c;
}

// With the camera's noise (the measured 0.02 px and a pessimistic 0.1 px) and drops, the
// hands that stop or hover 0.5 mm or more beyond the clearance (≥ 3.8σ at 0.1 px) are
// never predicted.
TEST(CameraPrediction, NeverPredictsNoisyStopsAndHoversAboveTheClearance) {
  const std::vector<ContactZone> zones = contact_zones(percussion());
  int checked = 0;
  for (double noise_px : {kV4l2CentroidNoisePx, 0.1}) {
    const CorpusConfig corpus = camera_corpus(5, 150, noise_px);
    const std::vector<Stroke> strokes = make_stroke_corpus(percussion(), corpus);
    for (const CameraModel& camera : corpus.cameras) {
      for (const PredictionConfig& config : tuned_presets(camera)) {
        for (const Stroke& s : strokes) {
          if (s.rate_hz != camera.rate_hz || !s.contacts.empty() || s.min_clearance_m < config.clearance_m + 0.0005)
            continue;
          ContactPredictor p(config);
          for (const PointerSample& sample : s.samples) {
            p.add(sample.t_ns, {sample.x, sample.y});
            ASSERT_FALSE(p.predict(zones)) << to_string(s.kind) << " shape " << s.shape << " at " << s.rate_hz
                                           << " Hz, σ " << noise_px << " px";
          }
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 2000);
}

//! Strikes that match no true contact (same bar within 25 ms, each contact at most once),
//! and true contacts with no strike, over a corpus at one rate through the strike route.
struct Tally {
  int contacts = 0, false_strikes = 0, missed = 0, predicted = 0;
};
Tally run_route(const std::vector<Stroke>& strokes, double rate_hz, const PredictionConfig& config) {
  Tally t;
  for (const Stroke& s : strokes) {
    if (s.rate_hz != rate_hz) continue;
    StrikeDetector detector(percussion(), ContactConfig{}, config);
    std::vector<Impact> strikes;
    for (const PointerSample& p : s.samples)
      if (auto i = detector.update(p.t_ns, {p.x, p.y})) strikes.push_back(*i);
    std::vector<bool> used(strikes.size(), false);
    for (const TrueContact& c : s.contacts) {
      ++t.contacts;
      bool found = false;
      for (std::size_t i = 0; i < strikes.size() && !found; ++i) {
        if (used[i] || strikes[i].target != c.target || std::llabs(strikes[i].t_ns - c.t_ns) > 25'000'000) continue;
        used[i] = found = true;
        t.predicted += strikes[i].predicted ? 1 : 0;
      }
      t.missed += found ? 0 : 1;
    }
    t.false_strikes += static_cast<int>(std::count(used.begin(), used.end(), false));
  }
  return t;
}

// Through the strike route, on a camera corpus the bench never saw (another seed), the tuned
// presets add no false and no missed strike to the exact solver's, and predict a share of
// the contacts.
TEST(CameraPrediction, AddsNoFalseOrMissedStrike) {
  for (double noise_px : {kV4l2CentroidNoisePx, 0.1}) {
    const CorpusConfig corpus = camera_corpus(11, 100, noise_px);
    const std::vector<Stroke> strokes = make_stroke_corpus(percussion(), corpus);
    for (const CameraModel& camera : corpus.cameras) {
      const Tally off = run_route(strokes, camera.rate_hz, prediction_off());
      ASSERT_GT(off.contacts, 300);
      for (const PredictionConfig& config : tuned_presets(camera)) {
        SCOPED_TRACE(std::to_string(camera.rate_hz) + " Hz, σ " + std::to_string(noise_px) + " px, braking " +
                     std::to_string(config.braking_m_per_s2) + ", speedup " + std::to_string(config.max_speedup_m_per_s2));
        const Tally on = run_route(strokes, camera.rate_hz, config);
        EXPECT_EQ(on.contacts, off.contacts);
        EXPECT_LE(on.false_strikes, off.false_strikes);
        EXPECT_LE(on.missed, off.missed);
        EXPECT_GE(on.predicted * 6, on.contacts);  // at least a sixth predicted (exact* at 120 Hz: 19 %)
      }
    }
  }
}

// Clean minimum-jerk strikes (the corpus's `strike` kind, no noise or drops) at 120 and
// 240 Hz: every prediction's contact time within −3.5 / +1 ms of the true one and its speed
// within −5 % / +75 % (a quadratic lags braking that is still building up, so speeds err
// high: measured 0 to +61 % at 120 Hz, +27 % at 240 Hz; times −2.6 to 0 ms); at least a
// third of the strikes predicted.
TEST(CameraPrediction, CleanStrikesWithinStatedBounds) {
  const std::vector<ContactZone> zones = contact_zones(percussion());
  for (double rate : kRates) {
    CameraModel camera = v4l2_camera(rate);
    CorpusConfig corpus;
    corpus.seed = 99;
    corpus.shapes_per_kind = 150;
    camera.noise_px = 0;
    camera.drop_probability = 0;
    corpus.cameras = {camera};
    const std::vector<Stroke> strokes = make_stroke_corpus(percussion(), corpus);
    for (const PredictionConfig& config : tuned_presets(camera)) {
      int contacts = 0, predicted = 0;
      double tmin = 0, tmax = 0, vmin = 0, vmax = 0;
      for (const Stroke& s : strokes) {
        if (s.kind != StrokeKind::strike) continue;
        ++contacts;
        ContactPredictor p(config);
        for (const PointerSample& sample : s.samples) {
          if (sample.t_ns >= s.contacts[0].t_ns) break;
          p.add(sample.t_ns, {sample.x, sample.y});
          if (const auto c = p.predict(zones)) {
            const double dt = static_cast<double>(c->t_ns - s.contacts[0].t_ns) * 1e-6;
            const double dv = 100.0 * (c->speed_m_per_s - s.contacts[0].speed_m_per_s) / s.contacts[0].speed_m_per_s;
            tmin = std::min(tmin, dt);
            tmax = std::max(tmax, dt);
            vmin = std::min(vmin, dv);
            vmax = std::max(vmax, dv);
            EXPECT_EQ(static_cast<int>(c->zone), s.contacts[0].target);
            ++predicted;
            break;
          }
        }
      }
      if (std::getenv("MALLET_PRINT_BOUNDS"))
        std::printf("%.0f Hz braking %.0f speedup %.0f: %d/%d t [%.2f, %.2f] ms v [%.1f, %.1f] %%\n", rate,
                    config.braking_m_per_s2, config.max_speedup_m_per_s2, predicted, contacts, tmin, tmax, vmin, vmax);
      SCOPED_TRACE(std::to_string(rate) + " Hz, speedup " + std::to_string(config.max_speedup_m_per_s2));
      ASSERT_GT(contacts, 100);
      EXPECT_GE(predicted * 3, contacts);
      EXPECT_GE(tmin, -3.5);
      EXPECT_LE(tmax, 1.0);
      EXPECT_GE(vmin, -5.0);
      EXPECT_LE(vmax, 75.0);
    }
  }
}

}  // namespace
}  // namespace mallet
