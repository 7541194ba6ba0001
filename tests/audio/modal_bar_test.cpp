// The acoustic note, measured from the rendered samples: every bar of the shipped scene is
// in tune, the partials sit at the configured ratios, a faster strike is louder and
// brighter but never beyond full scale, the sub-sample delay is exact, and nothing at or
// above 0.45·fs is rendered.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "audio/modal_bar.hpp"
#include "core/config/instruments_config.hpp"
#include "core/tuning.hpp"
#include "test_paths.hpp"

namespace mallet::audio {
namespace {

constexpr int kRate = 48000;
constexpr std::size_t kLength = std::size_t{1} << 18;  // 5.5 s at 48 kHz: the scene's presets decay by > 100 dB

const std::vector<ModalPreset>& shipped_presets() {
  static const std::vector<ModalPreset> presets = config::load_instruments(test::config_dir() / "instruments.toml");
  return presets;
}

const ModalPreset& shipped(std::string_view name) {  // by value: no reference to a temporary
  for (const ModalPreset& p : shipped_presets())
    if (p.name == name) return p;
  ADD_FAILURE() << "no preset " << name;
  return shipped_presets().front();
}

std::vector<double> render(const ModalPreset& preset, double f0, double speed, double delay_s = 0.0,
                           int rate = kRate, std::size_t n = kLength) {
  ModalBarVoice voice;
  voice.strike(preset, f0, speed, delay_s, rate);
  std::vector<double> y(n);
  for (double& s : y) s = voice.tick();
  return y;
}

// In-place radix-2 FFT (the size is a power of two).
void fft(std::vector<std::complex<double>>& x) {
  const std::size_t n = x.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(x[i], x[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = -2.0 * std::numbers::pi / static_cast<double>(len);
    const std::complex<double> w_len(std::cos(angle), std::sin(angle));
    for (std::size_t i = 0; i < n; i += len) {
      std::complex<double> w(1.0, 0.0);
      for (std::size_t k = 0; k < len / 2; ++k) {
        const std::complex<double> u = x[i + k], v = x[i + k + len / 2] * w;
        x[i + k] = u + v;
        x[i + k + len / 2] = u - v;
        w *= w_len;
      }
    }
  }
}

// |X|² of a whole decayed note (no window is needed: it starts at sin(0) and has died
// away before the end, so each partial's line is a Lorentzian without leakage).
struct BarSpectrum {
  std::vector<double> power;
  double bin_hz = 0;

  BarSpectrum(const std::vector<double>& y, int rate) {
    std::vector<std::complex<double>> x(y.begin(), y.end());
    fft(x);
    power.resize(x.size() / 2);
    for (std::size_t i = 0; i < power.size(); ++i) power[i] = std::norm(x[i]);
    bin_hz = static_cast<double>(rate) / static_cast<double>(x.size());
  }

  std::size_t bin(double hz) const {
    return std::min(power.size() - 1, static_cast<std::size_t>(std::max(0.0, hz / bin_hz)));
  }

  //! The strongest line in [lo, hi] Hz, refined between bins: 1/|X|² of a Lorentzian is a
  //! parabola in f, so the vertex of the parabola through three bins is its centre.
  double peak_hz(double lo, double hi) const {
    std::size_t best = std::max<std::size_t>(bin(lo), 1);
    for (std::size_t i = best; i <= std::min(bin(hi), power.size() - 2); ++i)
      if (power[i] > power[best]) best = i;
    const double a = 1.0 / power[best - 1], b = 1.0 / power[best], c = 1.0 / power[best + 1];
    const double offset = 0.5 * (a - c) / (a - 2.0 * b + c);
    return (static_cast<double>(best) + offset) * bin_hz;
  }

  double max_in(double lo, double hi) const {
    double m = 0;
    for (std::size_t i = bin(lo); i <= bin(hi); ++i) m = std::max(m, power[i]);
    return m;
  }

  double energy(double lo, double hi) const {
    double e = 0;
    for (std::size_t i = bin(lo); i <= bin(hi); ++i) e += power[i];
    return e;
  }
};

double cents(double measured, double expected) { return 1200.0 * std::log2(measured / expected); }

// The strike law as documented in core/modal_preset.hpp, written out independently.
std::vector<double> documented_amplitudes(const ModalPreset& p, double v) {
  const double s = v / p.reference_speed_m_per_s, l = p.loudness;
  const double e = s <= 1 ? l * s : 1 - (1 - l) * (1 - l) / (1 - 2 * l + l * s);
  const double sigma = e / l;
  std::vector<double> w;
  double total = 0;
  for (const Mode& m : p.modes) {
    w.push_back(m.gain * std::min(4.0, std::pow(sigma, p.brightness * (m.ratio - 1) / m.ratio)));
    total += w.back();
  }
  for (double& a : w) a *= e / total;
  return w;
}

// Σ a_k·e^(−b_k·t)·sin(2π·r_k·f0·t) over the modes below 0.45·rate, in long double.
double analytic(const ModalPreset& p, const std::vector<double>& a, double f0, int rate, double t) {
  long double sum = 0;
  for (std::size_t k = 0; k < p.modes.size(); ++k) {
    const double f = p.modes[k].ratio * f0;
    if (f >= 0.45 * rate) continue;
    sum += a[k] * std::exp(-static_cast<long double>(p.modes[k].decay_per_s) * t) *
           std::sin(2.0L * std::numbers::pi_v<long double> * static_cast<long double>(f) * t);
  }
  return static_cast<double>(sum);
}

TEST(ModalBar, EveryBarOfTheShippedSceneIsWithinFiveCentsOfEqualTemperament) {
  const Scene& scene = test::percussion();
  const std::vector<ModalPreset> presets = config::load_instruments(scene.instruments_file);
  ASSERT_EQ(scene.targets.size(), 16u);
  for (const Target& t : scene.targets) {
    const ModalPreset* preset = nullptr;
    for (const Instrument& inst : scene.instruments)
      if (inst.name == t.instrument)
        for (const ModalPreset& p : presets)
          if (p.name == inst.voice) preset = &p;
    ASSERT_NE(preset, nullptr) << t.instrument;
    const double expected = note_frequency_hz(t.note, 440.0);  // 440·2^((n−69)/12)
    const BarSpectrum spectrum(render(*preset, t.frequency_hz, preset->reference_speed_m_per_s), kRate);
    // The fundamental is the strongest line of the whole audible spectrum.
    const double measured = spectrum.peak_hz(20.0, 20000.0);
    EXPECT_LT(std::fabs(cents(measured, expected)), 5.0)
        << t.instrument << " note " << t.note << ": " << measured << " Hz for " << expected << " Hz";
  }
}

TEST(ModalBar, RenderedPartialsAreAtTheConfiguredRatios) {
  struct Case {
    std::string preset;
    int note;
    std::vector<double> ratios;  // the bar's physics, not read back from the file
  } cases[] = {{"glockenspiel", 84, {2.756, 5.404}}, {"glockenspiel", 96, {2.756, 5.404}},
               {"xylophone", 72, {3.0}},             {"xylophone", 84, {3.0}}};
  for (const Case& c : cases) {
    const double f0 = note_frequency_hz(c.note);
    const BarSpectrum spectrum(render(shipped(c.preset), f0, 3.0), kRate);
    const double fundamental = spectrum.peak_hz(0.9 * f0, 1.1 * f0);
    for (double r : c.ratios) {
      // Search ±10% around the expected partial: a bar with the wrong ratio (e.g. 3 instead
      // of 2.756) still has its line in the window and fails the 0.5% check.
      const double partial = spectrum.peak_hz(0.9 * r * f0, 1.1 * r * f0);
      EXPECT_NEAR(partial / fundamental, r, 0.005 * r) << c.preset << " note " << c.note;
    }
  }
}

TEST(ModalBar, FasterStrikeIsLouderAndBrighterAndZeroAtRest) {
  const double speeds[] = {0.25, 0.75, 1.5, 3.0, 6.0, 10.0, 100.0};
  for (const char* name : {"xylophone", "glockenspiel", "marimba", "vibraphone"}) {
    const ModalPreset& p = shipped(name);
    const double f0 = note_frequency_hz(84);
    double last_peak = 0, last_energy = 0, last_share = 0, last_fundamental = 0;
    for (double v : speeds) {
      const std::vector<double> y = render(p, f0, v, 0.0, kRate, kLength / 2);
      double peak = 0, energy = 0;
      for (double s : y) {
        peak = std::max(peak, std::fabs(s));
        energy += s * s;
      }
      const BarSpectrum spectrum(y, kRate);
      const double share = spectrum.energy(1.5 * f0, 0.5 * kRate) / spectrum.energy(0, 0.5 * kRate);
      const double fundamental = spectrum.max_in(0.95 * f0, 1.05 * f0);
      EXPECT_GT(peak, last_peak) << name << " v = " << v;
      // Brighter does not mean a quieter fundamental: a harder strike excites every mode more.
      EXPECT_GT(fundamental, last_fundamental) << name << " v = " << v;
      EXPECT_GT(energy, last_energy) << name << " v = " << v;
      EXPECT_GT(share, last_share * 1.01) << name << " v = " << v << ": overtones' share of the energy";
      last_peak = peak;
      last_energy = energy;
      last_share = share;
      last_fundamental = fundamental;
    }
  }
  for (double v : {0.0, -1.0, std::nan("")}) {
    ModalBarVoice voice;
    voice.strike(shipped("xylophone"), 523.25, v, 0.0, kRate);
    EXPECT_EQ(voice.envelope(), 0.0) << v;
    for (int i = 0; i < 4800; ++i) ASSERT_EQ(voice.tick(), 0.0) << "v = " << v << ", sample " << i;
  }
}

TEST(ModalBar, AtTheReferenceSpeedTheNoteStartsAtZeroWithTheConfiguredLoudness) {
  for (const ModalPreset& p : shipped_presets()) {
    ModalBarVoice voice;
    voice.strike(p, 440.0, p.reference_speed_m_per_s, 0.0, kRate);
    EXPECT_NEAR(voice.envelope(), p.loudness, 1e-12) << p.name;
    EXPECT_EQ(voice.tick(), 0.0) << p.name;  // every mode starts at sin(0)
  }
}

TEST(ModalBar, BrightnessZeroKeepsTheTimbre) {
  ModalPreset p = shipped("glockenspiel");
  p.brightness = 0.0;
  const double f0 = note_frequency_hz(88);
  const BarSpectrum slow(render(p, f0, 0.5), kRate), fast(render(p, f0, 8.0), kRate);
  const double share_slow = slow.energy(1.5 * f0, 0.5 * kRate) / slow.energy(0, 0.5 * kRate);
  const double share_fast = fast.energy(1.5 * f0, 0.5 * kRate) / fast.energy(0, 0.5 * kRate);
  EXPECT_NEAR(share_fast, share_slow, 1e-9);
}

TEST(ModalBar, VeryFastStrikesStayBelowFullScaleWithoutNaN) {
  for (const ModalPreset& p : shipped_presets()) {
    for (double v : {10.0, 100.0, 1e6, std::numeric_limits<double>::infinity()}) {
      for (int note : {60, 72, 84, 96, 108}) {
        ModalBarVoice voice;
        voice.strike(p, note_frequency_hz(note), v, 0.0, kRate);
        EXPECT_LE(voice.envelope(), 1.0 + 1e-15) << p.name << " v = " << v;  // E(inf) = 1, to rounding
        for (int i = 0; i < kRate / 2; ++i) {
          const double y = voice.tick();
          ASSERT_TRUE(std::isfinite(y)) << p.name << " v = " << v << " note " << note << " sample " << i;
          ASSERT_LE(std::fabs(y), 1.0) << p.name << " v = " << v << " note " << note << " sample " << i;
        }
      }
    }
  }
  // The law's compression alone, with no other mode's phase to hide behind: one undamped
  // mode at full loudness peaks at full scale, not above, at 100 m/s.
  ModalPreset loud{"loud", {{1.0, 1.0, 0.0}}, 1.0, 2.0, 1.0};
  EXPECT_LE(ModalBarVoice::note_amplitude(loud, 100.0), 1.0);
  ModalBarVoice voice;
  voice.strike(loud, 1000.0, 100.0, 0.0, kRate);
  double peak = 0;
  for (int i = 0; i < kRate; ++i) peak = std::max(peak, std::fabs(voice.tick()));
  EXPECT_LE(peak, 1.0);
  EXPECT_GT(peak, 0.999);
  EXPECT_LT(ModalBarVoice::note_amplitude(shipped("xylophone"), 100.0), 1.0);
  EXPECT_GT(ModalBarVoice::note_amplitude(shipped("xylophone"), 100.0),
            ModalBarVoice::note_amplitude(shipped("xylophone"), 10.0));
}

TEST(ModalBar, SubSampleDelayGivesTheAnalyticSumAtThatInstant) {
  const ModalPreset& p = shipped("glockenspiel");
  const double f0 = note_frequency_hz(91);
  for (double delay : {0.0, 0.37 / kRate, 0.999 / kRate, 2.5e-3}) {
    for (double v : {0.7, 1.5, 4.0}) {
      const std::vector<double> y = render(p, f0, v, delay, kRate, kRate);
      const std::vector<double> a = documented_amplitudes(p, v);
      double worst = 0;
      for (std::size_t n = 0; n < y.size(); ++n) {
        const double t = static_cast<double>(n) / kRate + delay;
        worst = std::max(worst, std::fabs(y[n] - analytic(p, a, f0, kRate, t)));
      }
      EXPECT_LT(worst, 1e-9) << "delay " << delay << " s, v = " << v;
    }
  }
}

TEST(ModalBar, ModesAtOrAboveFortyFivePercentOfTheRateAreLeftOut) {
  constexpr int kLowRate = 8000;  // 0.45·fs = 3600 Hz
  // Xylophone C6 (1046.5 Hz): 1×, 3× = 3139 Hz stay; 6× = 6279 Hz would alias to 1721 Hz.
  const ModalPreset& xylophone = shipped("xylophone");
  const double f0 = note_frequency_hz(84);
  ModalBarVoice voice;
  voice.strike(xylophone, f0, 3.0, 0.0, kLowRate);
  EXPECT_EQ(voice.active_modes(), 2);
  voice.strike(xylophone, f0, 3.0, 0.0, kRate);
  EXPECT_EQ(voice.active_modes(), 3);

  const std::vector<double> y = render(xylophone, f0, 3.0, 0.0, kLowRate, std::size_t{1} << 16);
  const BarSpectrum spectrum(y, kLowRate);
  const double alias_hz = kLowRate - 6.0 * f0;
  const double fundamental = spectrum.max_in(0.95 * f0, 1.05 * f0);
  // Had the 6× mode been rendered, its alias would stand ~27 dB below the fundamental;
  // what is there is the other lines' skirts, ~50 dB below.
  EXPECT_LT(spectrum.max_in(alias_hz - 30.0, alias_hz + 30.0), 1e-4 * fundamental);
  const std::vector<double> a = documented_amplitudes(xylophone, 3.0);
  for (std::size_t n = 0; n < y.size(); ++n)
    ASSERT_NEAR(y[n], analytic(xylophone, a, f0, kLowRate, static_cast<double>(n) / kLowRate), 1e-9) << n;

  // Exactly at 0.45·fs is out; just below is in; a fundamental up there is silence.
  ModalPreset edge{"edge", {{1.0, 1.0, 5.0}, {4.5, 0.5, 5.0}}, 0.3, 2.0, 1.0};
  voice.strike(edge, 800.0, 2.0, 0.0, kLowRate);  // 4.5 × 800 = 3600 Hz exactly
  EXPECT_EQ(voice.active_modes(), 1);
  voice.strike(edge, 799.9, 2.0, 0.0, kLowRate);
  EXPECT_EQ(voice.active_modes(), 2);
  voice.strike(edge, 3600.0, 2.0, 0.0, kLowRate);
  EXPECT_EQ(voice.active_modes(), 0);
  EXPECT_EQ(voice.envelope(), 0.0);
  EXPECT_EQ(voice.tick(), 0.0);
}

TEST(ModalBar, EnvelopeIsTheSumOfTheModesAndBoundsTheOutput) {
  const ModalPreset& p = shipped("glockenspiel");
  ModalBarVoice voice;
  voice.strike(p, note_frequency_hz(86), 2.0, 0.0, kRate);
  const std::vector<double> a = documented_amplitudes(p, 2.0);
  for (int n = 0; n < kRate; ++n) {
    const double t = static_cast<double>(n) / kRate;
    double expected = 0;
    for (std::size_t k = 0; k < a.size(); ++k) expected += a[k] * std::exp(-p.modes[k].decay_per_s * t);
    ASSERT_NEAR(voice.envelope(), expected, 1e-9) << n;
    ASSERT_LE(std::fabs(voice.tick()), expected + 1e-12) << n;
  }
  voice.stop();
  EXPECT_EQ(voice.envelope(), 0.0);
  EXPECT_EQ(voice.tick(), 0.0);
}

}  // namespace
}  // namespace mallet::audio

namespace mallet::audio {
namespace {

// The engine renders voices in blocks (add_to); the block path must be the tick path.
TEST(ModalBar, BlockRenderingEqualsTickByTickForEveryPreset) {
  for (const ModalPreset& preset : config::load_instruments(test::config_dir() / "instruments.toml")) {
    ModalBarVoice a, b;
    a.strike(preset, 659.26, 1.2, 4e-6, 48000);
    b.strike(preset, 659.26, 1.2, 4e-6, 48000);
    std::vector<double> blocks(6000, 0.0);
    for (int first = 0, n = 1; first < 6000; first += n, n = n % 500 + 13)
      b.add_to(blocks.data() + first, std::min(n, 6000 - first));
    for (std::size_t i = 0; i < blocks.size(); ++i) ASSERT_EQ(blocks[i], a.tick()) << preset.name << " " << i;
  }
}

}  // namespace
}  // namespace mallet::audio
