// The paper's MIDI route: FluidSynth with Debian's GM soundfont, rendered in our callback.
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "audio/fluidsynth_route.hpp"
#include "test_paths.hpp"

namespace mallet::audio {
namespace {

const char* kSoundfont = "/usr/share/sounds/sf2/TimGM6mb.sf2";

std::vector<double> render_note(int program, int note, double speed, int frames) {
  FluidSynthRoute route(kSoundfont, 48000, {program});
  route.note_on(0, note, speed);
  std::vector<double> out(static_cast<std::size_t>(frames), 0.0);
  route.render(out.data(), frames);
  return out;
}

// |DFT| of x at frequency f (Hann window): a zoom into the spectrum around the note.
double magnitude_at(const std::vector<double>& x, double f, int fs) {
  std::complex<double> acc = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) / n);
    acc += w * x[i] * std::polar(1.0, -2 * std::numbers::pi * f * static_cast<double>(i) / fs);
  }
  return std::abs(acc);
}

// The strongest frequency within a semitone of `expected`, in cents from it.
double cents_off(const std::vector<double>& x, double expected, int fs) {
  double best_f = expected, best = 0;
  for (double c = -100; c <= 100; c += 0.5) {
    const double f = expected * std::exp2(c / 1200);
    const double m = magnitude_at(x, f, fs);
    if (m > best) {
      best = m;
      best_f = f;
    }
  }
  return 1200 * std::log2(best_f / expected);
}

TEST(FluidSynthRoute, MissingSoundfontNamesTheDebianPackage) {
  try {
    FluidSynthRoute route("/nonexistent/gm.sf2", 48000, {13});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("timgm6mb-soundfont"), std::string::npos) << e.what();
  }
}

TEST(FluidSynthRoute, VelocityFollowsSpeedWithinMidiRange) {
  EXPECT_EQ(FluidSynthRoute::velocity_for(0.0), 1);
  EXPECT_EQ(FluidSynthRoute::velocity_for(2.0), 100);
  EXPECT_EQ(FluidSynthRoute::velocity_for(100.0), 127);
  EXPECT_LT(FluidSynthRoute::velocity_for(0.5), FluidSynthRoute::velocity_for(1.0));
}

TEST(FluidSynthRoute, XylophoneAndGlockenspielSoundAtTheirNotesPitch) {
  struct Case {
    int program, note;
  } cases[] = {{13, 72}, {13, 79}, {13, 84}, {9, 84}, {9, 91}, {9, 96}};
  for (const Case& c : cases) {
    const auto y = render_note(c.program, c.note, 1.5, 9600);  // 200 ms
    double energy = 0;
    for (double s : y) energy += s * s;
    ASSERT_GT(energy, 1e-3) << "program " << c.program << " note " << c.note;
    const double f0 = 440.0 * std::exp2((c.note - 69) / 12.0);
    // A sampled instrument is as well tuned as its samples: TimGM6mb's are within 25 cents
    // (a quarter of a semitone; measured: xylophone ≤ 10, glockenspiel 10–20 at the top).
    EXPECT_LT(std::fabs(cents_off(y, f0, 48000)), 25.0) << "program " << c.program << " note " << c.note;
  }
}

TEST(FluidSynthRoute, ThroughTheEngineTheNoteStartsWithinOneSynthBlockOfItsSample) {
  FluidSynthRoute route(kSoundfont, 48000, {13, 9});
  AudioEngine engine(test::percussion(), {ModalPreset{"x", {{1, 1, 1}}, 0.3, 2, 1}, ModalPreset{"g", {{1, 1, 1}}, 0.3, 2, 1}},
                     EngineSettings{});
  engine.set_external_acoustic(&route);
  const Target& bar = test::percussion().targets[2];
  Impact impact;
  impact.t_ns = 10'000'000 + 3'000;  // sample 481 (between samples)
  impact.target = bar.id;
  impact.material = bar.material;
  impact.note = bar.note;
  impact.speed_m_per_s = 1.5;
  engine.post(impact);
  std::vector<float> out(2 * 4800);
  engine.process(out.data(), 4800);
  std::int64_t acoustic = -1, actuator = -1;
  for (std::int64_t i = 0; i < 4800; ++i) {
    if (acoustic < 0 && out[static_cast<std::size_t>(2 * i)] != 0.0f) acoustic = i;
    if (actuator < 0 && out[static_cast<std::size_t>(2 * i + 1)] != 0.0f) actuator = i;
  }
  EXPECT_EQ(actuator, 481);
  // FluidSynth applies a note-on at its next internal 64-frame block: measured, stated.
  EXPECT_GE(acoustic, 481);
  EXPECT_LT(acoustic, 481 + 64);
}

}  // namespace
}  // namespace mallet::audio
