// The actuator's measurement and inverse, on their own (no sound card): the exponential
// sweep, its deconvolution, the response's analysis and the bounded minimum-phase inverse,
// against a chain whose response is known exactly (audio/simulated_plant.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "audio/actuator_inverse.hpp"
#include "audio/actuator_response.hpp"
#include "audio/exp_sweep.hpp"
#include "audio/fft.hpp"
#include "audio/fir_filter.hpp"
#include "audio/simulated_plant.hpp"

namespace mallet::audio {
namespace {

constexpr int kRate = 48000;

double db(double v) { return 20 * std::log10(v); }

// The sweep played through the plant and recorded with a tail, with a little noise.
std::vector<double> impulse_through(SimulatedPlant& plant, const SweepSpec& spec, double noise = 1e-5) {
  const std::vector<double> sweep = exp_sweep(spec);
  std::vector<double> recorded(sweep.size() + kRate / 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, noise);
  for (std::size_t i = 0; i < recorded.size(); ++i)
    recorded[i] = plant.tick(i < sweep.size() ? sweep[i] : 0.0) + n(rng);
  return deconvolve_sweep(recorded, sweep, spec, 8192);
}

TEST(ExpSweep, RisesFromF1ToF2AtTheLevelAskedAndFadesInAndOut) {
  const SweepSpec spec{.f1_hz = 20, .f2_hz = 2000, .duration_s = 2.0, .level_db = -20, .sample_rate_hz = kRate};
  const std::vector<double> x = exp_sweep(spec);
  ASSERT_EQ(x.size(), 96000u);
  double peak = 0;
  for (double v : x) peak = std::max(peak, std::abs(v));
  EXPECT_NEAR(peak, 0.1, 1e-4);
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_NEAR(x.back(), 0.0, 1e-6);
  // Zero crossings a quarter of the way in and near the end: the local frequency.
  const auto local_hz = [&](double t) {
    const auto from = static_cast<std::size_t>(t * kRate);
    int crossings = 0;
    std::size_t first = 0, last = 0;
    for (std::size_t i = from; i < from + 4800; ++i)
      if ((x[i] < 0) != (x[i + 1] < 0)) {
        if (!crossings) first = i;
        last = i;
        ++crossings;
      }
    return (crossings - 1) / 2.0 / (static_cast<double>(last - first) / kRate);
  };
  const double big_l = 2.0 / std::log(100.0);
  EXPECT_NEAR(local_hz(0.5), 20 * std::exp(0.55 / big_l), 0.05 * 20 * std::exp(0.55 / big_l));
  EXPECT_NEAR(local_hz(1.85), 20 * std::exp(1.9 / big_l), 0.05 * 20 * std::exp(1.9 / big_l));
  EXPECT_THROW(exp_sweep({.f1_hz = 20, .f2_hz = 30000, .sample_rate_hz = kRate}), std::invalid_argument);
  EXPECT_THROW(exp_sweep({.level_db = 3}), std::invalid_argument);
}

TEST(ExpSweep, ARecordingOfTheSweepItselfDeconvolvesToAnImpulseAndADelayMovesIt) {
  const SweepSpec spec{.duration_s = 1.0, .sample_rate_hz = kRate};
  const std::vector<double> sweep = exp_sweep(spec);
  std::vector<double> recorded(sweep.size() + 1000, 0.0);
  std::copy(sweep.begin(), sweep.end(), recorded.begin() + 100);
  const std::vector<double> h = deconvolve_sweep(recorded, sweep, spec, 4096);
  const auto peak = std::max_element(h.begin(), h.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  EXPECT_EQ(peak - h.begin(), 100);
  // Band-limited to 20 Hz..2 kHz: the peak is the band's share of a unit impulse.
  EXPECT_NEAR(*peak, 2 * (2000.0 - 20.0) / kRate, 0.01);
}

TEST(ActuatorResponse, TheMeasuredMagnitudeDelayAndResonanceAreThePlantsOwn) {
  SimulatedPlant plant({.delay_samples = 37, .sample_rate_hz = kRate});
  const SweepSpec spec{.sample_rate_hz = kRate};
  const std::vector<double> h = impulse_through(plant, spec);
  const ActuatorResponse r = analyse_response(h, kRate, spec.f1_hz, spec.f2_hz);
  EXPECT_LT(r.band_low_hz, 80.0);
  EXPECT_GT(r.band_high_hz, 1400.0);
  int checked = 0;
  for (const ResponsePoint& p : r.points) {
    if (p.freq_hz < r.band_low_hz || p.freq_hz > r.band_high_hz) continue;
    EXPECT_NEAR(p.magnitude_db, db(std::abs(plant.response(p.freq_hz))), 0.5) << p.freq_hz << " Hz";
    ++checked;
  }
  EXPECT_GT(checked, 50);
  EXPECT_NEAR(r.delay_samples, 37.0, 1.0);
  EXPECT_FALSE(r.inverted);
  // The high-pass peaks a little above f0 (Q = 4): within a twelfth of an octave.
  EXPECT_NEAR(std::log2(r.resonance_hz / 180.0), 0.0, 1.0 / 12);
}

TEST(ActuatorResponse, ASensorWiredTheOtherWayRoundIsSaidAndTheDelayIsUnchanged) {
  SimulatedPlant plant({.delay_samples = 200, .gain = -0.5, .sample_rate_hz = kRate});
  const SweepSpec spec{.sample_rate_hz = kRate};
  const ActuatorResponse r = analyse_response(impulse_through(plant, spec), kRate, spec.f1_hz, spec.f2_hz);
  EXPECT_TRUE(r.inverted);
  EXPECT_NEAR(r.delay_samples, 200.0, 1.0);
}

TEST(MinimumPhase, AMinimumPhaseFiltersMagnitudeGivesTheFilterBack) {
  // h = δ + 0.5 δ(n−1): zero at −0.5, inside the unit circle.
  const std::size_t n = 1024;
  const Spectrum h = real_dft(std::vector<double>{1.0, 0.5}, n);
  std::vector<double> magnitude(h.size());
  for (std::size_t k = 0; k < h.size(); ++k) magnitude[k] = std::abs(h[k]);
  const std::vector<double> back = inverse_real_dft(minimum_phase(magnitude, n), n);
  EXPECT_NEAR(back[0], 1.0, 1e-9);
  EXPECT_NEAR(back[1], 0.5, 1e-9);
  EXPECT_NEAR(back[2], 0.0, 1e-9);
}

TEST(ActuatorInverse, ThePlantAfterTheInverseIsFlatWhereTheGainLimitAllowsAndNeverLiftsMore) {
  SimulatedPlant plant({.sample_rate_hz = kRate});
  const SweepSpec spec{.sample_rate_hz = kRate};
  const std::vector<double> h = impulse_through(plant, spec);
  const ActuatorResponse r = analyse_response(h, kRate, spec.f1_hz, spec.f2_hz);
  const InverseFilter inverse = design_inverse(h, r, {.gain_limit_db = 12, .taps = 1024});
  ASSERT_EQ(inverse.taps.size(), 1024u);
  EXPECT_LE(inverse.max_gain_db, 12.0 + 0.1);
  EXPECT_LT(inverse.min_gain_db, -6.0);  // the resonance is cut
  int flat = 0;
  for (const ResponsePoint& p : r.points) {
    if (p.freq_hz < r.band_low_hz || p.freq_hz > r.band_high_hz) continue;
    // Where the plant needs less than the limit (with 3 dB to spare for the regulariser).
    if (p.magnitude_db < inverse.target_db - 9.0) continue;
    const double chain = db(std::abs(plant.response(p.freq_hz) * response_at(inverse.taps, p.freq_hz, kRate)));
    // 1024 taps leave up to ~1 dB where the regulariser and the cut meet (measured: 0.9 dB).
    EXPECT_NEAR(chain, inverse.target_db, 1.5) << p.freq_hz << " Hz";
    ++flat;
  }
  EXPECT_GT(flat, 40);
  // Minimum phase: its energy is at the front, and its latency is short.
  double front = 0, all = 0;
  for (std::size_t i = 0; i < inverse.taps.size(); ++i) {
    all += inverse.taps[i] * inverse.taps[i];
    if (i < 64) front += inverse.taps[i] * inverse.taps[i];
  }
  EXPECT_GT(front / all, 0.9);
  // Against the resonance its group delay is negative: it takes the resonance's delay away.
  EXPECT_LT(inverse.latency_samples, 0.0);
  EXPECT_GT(inverse.latency_samples, -240.0);
}

TEST(ActuatorInverse, ARefusedSpecOrAResponseWithoutABandIsAnError) {
  SimulatedPlant plant({.sample_rate_hz = kRate});
  const SweepSpec spec{.sample_rate_hz = kRate};
  const std::vector<double> h = impulse_through(plant, spec);
  const ActuatorResponse r = analyse_response(h, kRate, spec.f1_hz, spec.f2_hz);
  EXPECT_THROW(design_inverse(h, r, {.gain_limit_db = 0}), std::invalid_argument);
  EXPECT_THROW(design_inverse(h, r, {.taps = 4}), std::invalid_argument);
  ActuatorResponse empty = r;
  empty.band_low_hz = empty.band_high_hz = 100;
  EXPECT_THROW(design_inverse(h, empty, {}), std::invalid_argument);
}

}  // namespace
}  // namespace mallet::audio
