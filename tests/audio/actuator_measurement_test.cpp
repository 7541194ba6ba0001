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
#include "audio/felt_signal.hpp"
#include "audio/fft.hpp"
#include "audio/fir_filter.hpp"
#include "audio/simulated_plant.hpp"

namespace mallet::audio {
namespace {

constexpr int kSweepRate = 48000;

double db(double v) { return 20 * std::log10(v); }

// The sweep played through the plant and recorded with a tail, with a little noise; the
// response from kDeconvolutionPre samples before the sweep's first sample.
std::vector<double> impulse_through(SimulatedPlant& plant, const SweepSpec& spec, double noise = 1e-5) {
  const std::vector<double> sweep = exp_sweep(spec);
  std::vector<double> recorded(sweep.size() + kSweepRate / 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, noise);
  for (std::size_t i = 0; i < recorded.size(); ++i)
    recorded[i] = plant.tick(i < sweep.size() ? sweep[i] : 0.0) + n(rng);
  return deconvolve_sweep(recorded, sweep, spec, kDeconvolutionPre + 8192);
}

TEST(ExpSweep, RisesFromF1ToF2AtTheLevelAskedAndFadesInAndOut) {
  const SweepSpec spec{.f1_hz = 20, .f2_hz = 2000, .duration_s = 2.0, .level_db = -20, .sample_rate_hz = kSweepRate};
  const std::vector<double> x = exp_sweep(spec);
  ASSERT_EQ(x.size(), 96000u);
  double peak = 0;
  for (double v : x) peak = std::max(peak, std::abs(v));
  EXPECT_NEAR(peak, 0.1, 1e-4);
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_NEAR(x.back(), 0.0, 1e-6);
  // Zero crossings a quarter of the way in and near the end: the local frequency.
  const auto local_hz = [&](double t) {
    const auto from = static_cast<std::size_t>(t * kSweepRate);
    int crossings = 0;
    std::size_t first = 0, last = 0;
    for (std::size_t i = from; i < from + 4800; ++i)
      if ((x[i] < 0) != (x[i + 1] < 0)) {
        if (!crossings) first = i;
        last = i;
        ++crossings;
      }
    return (crossings - 1) / 2.0 / (static_cast<double>(last - first) / kSweepRate);
  };
  const double big_l = 2.0 / std::log(100.0);
  EXPECT_NEAR(local_hz(0.5), 20 * std::exp(0.55 / big_l), 0.05 * 20 * std::exp(0.55 / big_l));
  EXPECT_NEAR(local_hz(1.85), 20 * std::exp(1.9 / big_l), 0.05 * 20 * std::exp(1.9 / big_l));
  EXPECT_THROW(exp_sweep({.f1_hz = 20, .f2_hz = 30000, .sample_rate_hz = kSweepRate}), std::invalid_argument);
  EXPECT_THROW(exp_sweep({.level_db = 3}), std::invalid_argument);
}

TEST(ExpSweep, ARecordingOfTheSweepItselfDeconvolvesToAnImpulseAndADelayMovesIt) {
  const SweepSpec spec{.duration_s = 1.0, .sample_rate_hz = kSweepRate};
  const std::vector<double> sweep = exp_sweep(spec);
  std::vector<double> recorded(sweep.size() + 1000, 0.0);
  std::copy(sweep.begin(), sweep.end(), recorded.begin() + 100);
  const std::vector<double> h = deconvolve_sweep(recorded, sweep, spec, 16384, 8192);
  const auto peak = std::max_element(h.begin(), h.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  EXPECT_EQ(peak - h.begin(), 8192 + 100);
  // Flat to within 0.05 dB over the sweep (its fades and edges divided out).
  for (double f : {22.0, 25.0, 40.0, 100.0, 1000.0, 1900.0})
    EXPECT_NEAR(db(std::abs(response_at(h, f, kSweepRate))), 0.0, 0.05) << f << " Hz";
  // Band-limited to 20 Hz..2 kHz: the peak is the band's share of a unit impulse.
  EXPECT_NEAR(*peak, 2 * (2000.0 - 20.0) / kSweepRate, 0.01);
}

TEST(ActuatorResponse, TheMeasuredMagnitudeDelayAndResonanceAreThePlantsOwn) {
  struct Case {
    PlantKind kind;
    double band_low_below, band_high_above;
  };
  for (const Case& c : {Case{PlantKind::low_pass, 30.0, 400.0}, Case{PlantKind::high_pass, 80.0, 1400.0}}) {
    SimulatedPlant plant({.kind = c.kind, .delay_samples = 37, .sample_rate_hz = kSweepRate});
    const SweepSpec spec{.sample_rate_hz = kSweepRate};
    const std::vector<double> h = impulse_through(plant, spec);
    const ActuatorResponse r = analyse_response(h, kSweepRate, spec.f1_hz, spec.f2_hz, 30.0, kDeconvolutionPre);
    EXPECT_LT(r.band_low_hz, c.band_low_below);
    EXPECT_GT(r.band_high_hz, c.band_high_above);
    int checked = 0;
    for (const ResponsePoint& p : r.points) {
      if (p.freq_hz < r.band_low_hz || p.freq_hz > r.band_high_hz) continue;
      EXPECT_NEAR(p.magnitude_db, db(std::abs(plant.response(p.freq_hz))), 0.1) << p.freq_hz << " Hz";
      ++checked;
    }
    EXPECT_GT(checked, 30);
    // Within the sample; what the chain does beyond the sweep is not measured (header).
    EXPECT_NEAR(r.delay_samples, 37.0, 1.0);
    EXPECT_FALSE(r.inverted);
    // The high-pass peaks a little above f0, the low-pass a little below (Q = 4).
    EXPECT_NEAR(std::log2(r.resonance_hz / 180.0), 0.0, 1.0 / 12);
  }
}

TEST(ActuatorResponse, ASensorWiredTheOtherWayRoundIsSaidAndTheDelayIsUnchanged) {
  SimulatedPlant plant({.delay_samples = 200, .gain = -0.5, .sample_rate_hz = kSweepRate});
  const SweepSpec spec{.sample_rate_hz = kSweepRate};
  const ActuatorResponse r = analyse_response(impulse_through(plant, spec), kSweepRate, spec.f1_hz, spec.f2_hz, 30.0, kDeconvolutionPre);
  EXPECT_TRUE(r.inverted);
  EXPECT_NEAR(r.delay_samples, 200.0, 1.5);
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

TEST(ActuatorInverse, ThePlantAfterTheInverseIsFlatOverTheBandAndNeverLiftedMoreThanTheLimit) {
  for (PlantKind kind : {PlantKind::low_pass, PlantKind::high_pass}) {
    SimulatedPlant plant({.kind = kind, .sample_rate_hz = kSweepRate});
    const SweepSpec spec{.sample_rate_hz = kSweepRate};
    const std::vector<double> h = impulse_through(plant, spec);
    const ActuatorResponse r = analyse_response(h, kSweepRate, spec.f1_hz, spec.f2_hz, 30.0, kDeconvolutionPre);
    const InverseFilter inverse = design_inverse(h, r, {.gain_limit_db = 12});
    ASSERT_EQ(inverse.taps.size(), 2048u);
    EXPECT_LE(inverse.max_gain_db, 12.0 + 0.1);
    EXPECT_LT(inverse.min_gain_db, -6.0);  // the resonance is cut
    int flat = 0;
    for (const ResponsePoint& p : r.points) {
      // Inside the band, an octave clear of its edges (where the target rolls off).
      if (p.freq_hz < 2 * r.band_low_hz || p.freq_hz > r.band_high_hz / 2) continue;
      const double chain = db(std::abs(plant.response(p.freq_hz) * response_at(inverse.taps, p.freq_hz, kSweepRate)));
      EXPECT_NEAR(chain, inverse.target_db, 1.0) << p.freq_hz << " Hz, kind " << static_cast<int>(kind);
      ++flat;
    }
    EXPECT_GT(flat, 20);
    // Minimum phase: its delay over the band is a small part of its length (a linear-phase
    // filter of the same magnitude would be delayed by half of it, 1024 samples).
    EXPECT_LT(std::abs(inverse.latency_samples), 256.0) << "kind " << static_cast<int>(kind);
  }
}

TEST(FeltSignal, AfterTheInverseEachTable1StrikeHasTable1sDecayAndFrequencyAndBeforeItNot) {
  // Wood and metal of Table 1, through the resonant plant, without and with its inverse.
  SimulatedPlant measured({.delay_samples = 300, .sample_rate_hz = kSweepRate});
  const SweepSpec spec{.sample_rate_hz = kSweepRate};
  const std::vector<double> h = impulse_through(measured, spec);
  const ActuatorResponse r = analyse_response(h, kSweepRate, spec.f1_hz, spec.f2_hz, 30.0, kDeconvolutionPre);
  const InverseFilter inverse = design_inverse(h, r, {});
  std::vector<Material> materials(2);
  materials[0].name = "wood";
  materials[0].actuator = {1.0, 80.0, 100.0};
  materials[1].name = "metal";
  materials[1].actuator = {2.0, 90.0, 300.0};
  const std::vector<FeltStrike> strikes = felt_strikes(materials, kSweepRate);
  ASSERT_EQ(strikes.size(), 6u);
  const std::size_t total = static_cast<std::size_t>(strikes.back().start) + kSweepRate / 2;
  double worst_before = 0;
  for (bool equalised : {false, true}) {
    const std::vector<float> played =
        render_felt(strikes, 0.2, equalised ? std::span<const double>(inverse.taps) : std::span<const double>(), total, kSweepRate);
    SimulatedPlant plant({.delay_samples = 300, .sample_rate_hz = kSweepRate});
    std::vector<double> felt(total);
    for (std::size_t i = 0; i < total; ++i) felt[i] = plant.tick(played[i]);
    const std::vector<FeltFit> fits = fit_felt(strikes, felt, r.delay_samples, kSweepRate);
    for (std::size_t k = 0; k < fits.size(); ++k) {
      ASSERT_TRUE(fits[k].fit.ok) << k;
      const double worst = std::max(std::abs(fits[k].decay_error), std::abs(fits[k].freq_error));
      if (equalised)
        EXPECT_LT(worst, 0.03) << strikes[k].material << " at " << strikes[k].speed_m_per_s << " m/s";
      else
        worst_before = std::max(worst_before, worst);
    }
  }
  EXPECT_GT(worst_before, 0.10);
}

TEST(ActuatorInverse, ARefusedSpecOrAResponseWithoutABandIsAnError) {
  SimulatedPlant plant({.sample_rate_hz = kSweepRate});
  const SweepSpec spec{.sample_rate_hz = kSweepRate};
  const std::vector<double> h = impulse_through(plant, spec);
  const ActuatorResponse r = analyse_response(h, kSweepRate, spec.f1_hz, spec.f2_hz, 30.0, kDeconvolutionPre);
  EXPECT_THROW(design_inverse(h, r, {.gain_limit_db = 0}), std::invalid_argument);
  EXPECT_THROW(design_inverse(h, r, {.taps = 4}), std::invalid_argument);
  ActuatorResponse empty = r;
  empty.band_low_hz = empty.band_high_hz = 100;
  EXPECT_THROW(design_inverse(h, empty, {}), std::invalid_argument);
}

}  // namespace
}  // namespace mallet::audio
