// Contact prediction on scripted strokes: the fit is exact on exact motion and its noise
// model is the least-squares one; on clean minimum-jerk strikes its contact time and
// speed stay within the bounds stated here; a hand that stops at or above the clearance
// is never predicted, for every shipped preset.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/contact_predictor.hpp"
#include "core/stroke_corpus.hpp"
#include "core/stop_above_check.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

constexpr Nanos kT0 = 40 * 86'400 * kNanosPerSecond;  // 40 days of uptime: differences only

std::vector<PredictionConfig> shipped_presets() {
  return {prediction_balanced(), prediction_exact(), prediction_eager()};
}

double plane_of(const Scene& scene, int target) {
  return scene.targets[static_cast<std::size_t>(target)].top_y + scene.mallet_radius_m;
}

TEST(ContactPredictorFit, ExactOnAParabolaAndOnAStraightLine) {
  PredictionConfig c = prediction_balanced();
  ContactPredictor p(c);
  const double y0 = 0.05, v = -1.3, a = 40.0, x0 = 0.1, vx = 0.2;
  for (int k = -3; k <= 0; ++k) {
    const double t = k * 0.01;
    p.add(kT0 + k * 10'000'000, {x0 + vx * t, y0 + v * t + 0.5 * a * t * t});
  }
  const auto f = p.fit();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->samples, 4);
  EXPECT_NEAR(f->y_m(0), y0, 1e-12);
  EXPECT_NEAR(f->vy_m_per_s(0), v, 1e-9);
  EXPECT_NEAR(f->ay_m_per_s2(0), a, 1e-6);
  EXPECT_NEAR(f->y_m(0.004), y0 + v * 0.004 + 0.5 * a * 0.004 * 0.004, 1e-12);
  EXPECT_NEAR(f->x_m, x0, 1e-12);
  EXPECT_NEAR(f->vx_m_per_s, vx, 1e-9);
  EXPECT_NEAR(f->rms_residual_m, 0.0, 1e-9);
  EXPECT_EQ(p.expected_interval_ns(), 10'000'000);
}

TEST(ContactPredictorFit, NoiseModelIsTheLeastSquaresCovariance) {
  // Three samples and three coefficients: the parabola passes through each sample, so a
  // sample's own noise is the fit's there, and nothing else's.
  PredictionConfig c;
  c.min_samples = 3;
  ContactPredictor p(c);
  for (int k = -2; k <= 0; ++k) p.add(kT0 + k * 10'000'000, {0.0, 0.1});
  const auto f = p.fit();
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->sigma_y_m(0.0, 0.001), 0.001, 1e-12);
  EXPECT_NEAR(f->sigma_y_m(-0.01, 0.001), 0.001, 1e-12);
  // v(0) = (3y₀ − 4y₋₁ + y₋₂) / 2Δt: σ·√26 / 2Δt.
  EXPECT_NEAR(f->sigma_vy_m_per_s(0.0, 0.001), 0.001 * std::sqrt(26.0) / 0.02, 1e-9);
  // Extrapolating grows the uncertainty.
  EXPECT_GT(f->sigma_y_m(0.01, 0.001), 0.001);
}

TEST(ContactPredictor, OffPredictsNothing) {
  ContactPredictor p(prediction_off());
  // 2 m/s down onto bar 0, 2 mm above its plane at the last sample.
  const Target& bar = percussion().targets[0];
  const double plane = plane_of(percussion(), 0);
  for (int k = -5; k <= 0; ++k) p.add(kT0 + k * 10'000'000, {bar.x_min, plane + 0.002 - 2.0 * k * 0.01});
  EXPECT_FALSE(p.predict(contact_zones(percussion())));
  EXPECT_EQ(p.verdict(), PredictionVerdict::off);
}

//! Clean minimum-jerk strikes (the corpus's `strike` kind without camera noise or drops),
//! every prediction's errors against the true contact.
struct CleanErrors {
  std::vector<double> time_ms, speed_pct;
  int contacts = 0;
};

CleanErrors clean_strike_errors(const PredictionConfig& config, double rate_hz) {
  CorpusConfig corpus;
  corpus.seed = 99;
  corpus.shapes_per_kind = 150;
  CameraModel camera = wii_camera(rate_hz);
  camera.noise_px = 0;
  camera.quantise_px = false;
  camera.drop_probability = 0;
  corpus.cameras = {camera};
  const std::vector<ContactZone> zones = contact_zones(percussion());
  CleanErrors e;
  for (const Stroke& s : make_stroke_corpus(percussion(), corpus)) {
    if (s.kind != StrokeKind::strike) continue;
    ++e.contacts;
    ContactPredictor p(config);
    for (const PointerSample& sample : s.samples) {
      if (sample.t_ns >= s.contacts[0].t_ns) break;  // the predictions made before the contact
      p.add(sample.t_ns, {sample.x, sample.y});
      if (const auto c = p.predict(zones)) {
        e.time_ms.push_back(static_cast<double>(c->t_ns - s.contacts[0].t_ns) * 1e-6);
        e.speed_pct.push_back(100.0 * (c->speed_m_per_s - s.contacts[0].speed_m_per_s) / s.contacts[0].speed_m_per_s);
        EXPECT_EQ(static_cast<int>(c->zone), s.contacts[0].target);
        break;
      }
    }
  }
  return e;
}

// Stated bounds on clean minimum-jerk strikes (0.2–4 m/s, contact anywhere from peak speed
// to late braking), for every shipped preset at 100 and 200 Hz: the predicted contact time
// within −2.5 / +1 ms of the true one (early, never by more than the ≈15 ms that haptics may
// lead vision), the predicted speed within −5 % / +60 % (a quadratic lags braking that is
// still building up, so speeds err high: measured +1 % to +58 %), and at least a quarter of
// the strikes predicted.
TEST(ContactPredictor, CleanMinimumJerkStrikesWithinStatedBounds) {
  for (const PredictionConfig& config : shipped_presets()) {
    for (double rate : {100.0, 200.0}) {
      const CleanErrors e = clean_strike_errors(config, rate);
      SCOPED_TRACE("rate " + std::to_string(rate) + ", braking " + std::to_string(config.braking_m_per_s2) +
                   ", speedup " + std::to_string(config.max_speedup_m_per_s2));
      ASSERT_GT(e.contacts, 100);
      EXPECT_GE(e.time_ms.size() * 4, static_cast<std::size_t>(e.contacts));
      const auto [tmin, tmax] = std::minmax_element(e.time_ms.begin(), e.time_ms.end());
      const auto [vmin, vmax] = std::minmax_element(e.speed_pct.begin(), e.speed_pct.end());
      EXPECT_GE(*tmin, -2.5);
      EXPECT_LE(*tmax, 1.0);
      EXPECT_GE(*vmin, -5.0);
      EXPECT_LE(*vmax, 60.0);
    }
  }
}

// The guarantee of test 6 (could_stop): a hand that stops clearance_m or more above a bar,
// its braking peaking at no more than half of braking_m_per_s2, is never predicted — on
// exact samples, for any peak speed in the corpus's range, stop height and sample phase,
// for every shipped preset. (Half: the quadratic lags braking that is building up, so its
// speed, and the stopping distance from it, run high; at 0.7 of it one stroke in 600 was.)
TEST(ContactPredictor, NeverPredictsAHandThatStopsAboveTheClearance) {
  int strokes = 0;
  for (const PredictionConfig& config : shipped_presets())
    for (double rate : {100.0, 200.0}) strokes += test::expect_stops_never_predicted(config, percussion(), 3, rate, kT0);
  EXPECT_EQ(strokes, 3 * 2 * 5 * 5 * 4);
}

// With camera noise and drops (the corpus), the hands that stop or hover 1.5 mm or more
// beyond the clearance (3.5σ of the camera's noise) are never predicted either.
TEST(ContactPredictor, NeverPredictsNoisyStopsAndHoversAboveTheClearance) {
  CorpusConfig corpus;
  corpus.seed = 5;
  corpus.shapes_per_kind = 150;
  const std::vector<ContactZone> zones = contact_zones(percussion());
  int checked = 0;
  for (const PredictionConfig& config : shipped_presets()) {
    for (const Stroke& s : make_stroke_corpus(percussion(), corpus)) {
      if (!s.contacts.empty() || s.min_clearance_m < config.clearance_m + 0.0015) continue;
      ContactPredictor p(config);
      for (const PointerSample& sample : s.samples) {
        p.add(sample.t_ns, {sample.x, sample.y});
        ASSERT_FALSE(p.predict(zones)) << to_string(s.kind) << " shape " << s.shape << " at " << s.rate_hz << " Hz";
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

}  // namespace
}  // namespace mallet
