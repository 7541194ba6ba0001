#include "app/bench/voice_cost.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

#include "audio/damped_oscillator.hpp"
#include "audio/fluidsynth_route.hpp"
#include "audio/modal_bar.hpp"
#include "core/app_config.hpp"

#ifdef MALLET_HAVE_STK
#include <stk/ModalBar.h>
#include <stk/Stk.h>
#endif

namespace mallet::app {

namespace {
volatile double g_sink;
}  // namespace

void keep(double value) { g_sink = value; }

double median_ns_per_unit(int runs, double units, const std::function<void()>& body) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    const auto a = Clock::now();
    body();
    t.push_back(std::chrono::duration<double, std::nano>(Clock::now() - a).count() / units);
  }
  std::nth_element(t.begin(), t.begin() + static_cast<long>(t.size() / 2), t.end());
  return t[t.size() / 2];
}

double direct_eq1_ns(const VibrationParams& eq1, int n, int rate_hz, int runs) {
  return median_ns_per_unit(runs, n, [&] {
    double acc = 0;
    for (int i = 0; i < n; ++i) acc += decaying_sine_unit_seconds(eq1, i / double(rate_hz));
    keep(acc);
  });
}

double rotator_ns(double frequency_hz, int n, int rate_hz, int runs) {
  audio::DampedOscillator osc;
  return median_ns_per_unit(runs, n, [&] {
    osc.start(1.0, 0.0, frequency_hz, 0.0, rate_hz);
    std::vector<double> buf(64);
    for (int i = 0; i < n; i += 64) osc.add_to(buf.data(), 64);
    keep(buf[7]);
  });
}

double modal_bar_ns(const ModalPreset& preset, double fundamental_hz, int n, int rate_hz, int runs) {
  audio::ModalBarVoice bar;
  return median_ns_per_unit(runs, n, [&] {
    bar.strike(preset, fundamental_hz, 1.5, 0.0, rate_hz);
    std::vector<double> buf(64);
    for (int i = 0; i < n; i += 64) bar.add_to(buf.data(), 64);
    keep(buf[7]);
  });
}

std::optional<double> stk_modal_bar_ns([[maybe_unused]] int n, [[maybe_unused]] int rate_hz,
                                       [[maybe_unused]] int runs) {
#ifdef MALLET_HAVE_STK
  stk::Stk::setSampleRate(rate_hz);
  stk::Stk::setRawwavePath("/usr/share/stk/rawwaves/");
  stk::ModalBar bar;
  bar.setPreset(1);  // STK's presets: 0 marimba, 1 vibraphone, ...
  return median_ns_per_unit(runs, n, [&] {
    bar.noteOn(523.25, 0.8);
    double acc = 0;
    for (int i = 0; i < n; ++i) acc += bar.tick();
    keep(acc);
  });
#else
  return std::nullopt;
#endif
}

double fluidsynth_ns_per_voice_frame(int n, int rate_hz, int runs) {
  const int notes = 16;
  audio::FluidSynthRoute route(AppConfig{}.audio.soundfont, rate_hz, {13, 9});
  std::vector<double> buf(64);
  return median_ns_per_unit(runs, double(n) * notes, [&] {
    for (int k = 0; k < notes; ++k) route.note_on(k % 2, 72 + k, 1.5);
    for (int i = 0; i < n; i += 64) route.render(buf.data(), 64);
    keep(buf[0]);
  });
}

}  // namespace mallet::app
