// The audio part of `mallet bench report`: per knob (oscillator method, modes per bar,
// block size, schedule-ahead) its cost against its error, measured against long-double
// references; and the peers (STK's ModalBar, FluidSynth) in the same run.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "audio/audio_setup.hpp"
#include "app/bench/bench_report.hpp"
#include "app/bench/first_sample_latency.hpp"
#include "app/bench/voice_cost.hpp"
#include "app/bench/exact_reference.hpp"
#include "audio/damped_oscillator.hpp"
#include "audio/denormals.hpp"
#include "audio/fluidsynth_route.hpp"
#include "audio/modal_bar.hpp"
#include "core/config/instruments_config.hpp"
#include "core/quality.hpp"
#include "core/vibration.hpp"

#include <fmt/format.h>

namespace mallet::app {
namespace {

constexpr int kFs = 48000;

//! The note's reference over n samples at kFs (exact_reference.hpp).
std::vector<long double> note_reference(const ModalPreset& p, double f0, double v, int n) {
  const NoteReference note(p, f0, v, kFs);
  std::vector<long double> y(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) y[static_cast<std::size_t>(i)] = note(static_cast<long double>(i) / kFs);
  return y;
}

//! The largest component of the error's spectrum relative to the reference's largest, dB
//! (Hann window, a plain DFT of n samples at n/2 bins).
double spectral_error_db(const std::vector<double>& x, const std::vector<long double>& ref, int n) {
  std::vector<std::complex<double>> twiddle(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) twiddle[static_cast<std::size_t>(i)] = std::polar(1.0, -2.0 * std::numbers::pi * i / n);
  double max_err = 0, max_ref = 0;
  for (int k = 1; k < n / 2; ++k) {
    std::complex<double> e{}, r{};
    for (int i = 0; i < n; ++i) {
      const double hann = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n);
      const auto tw = twiddle[static_cast<std::size_t>((static_cast<long>(k) * i) % n)];
      const double rv = static_cast<double>(ref[static_cast<std::size_t>(i)]);
      e += hann * (x[static_cast<std::size_t>(i)] - rv) * tw;
      r += hann * rv * tw;
    }
    max_err = std::max(max_err, std::abs(e));
    max_ref = std::max(max_ref, std::abs(r));
  }
  return 20.0 * std::log10(std::max(max_err, 1e-300) / max_ref);
}

}  // namespace

void measure_audio_trades(const Scene& scene, const ReportOptions& o, ReportSections& out) {
  const int runs = o.quick ? 1 : 7;
  const int n = o.quick ? kFs / 20 : kFs * 2;  // samples per timing
  auto presets_where = [](const std::function<bool(const QualityKnobs&)>& uses) {
    std::string names;
    for (const auto& [q, quality] : kQualityNames)
      if (uses(quality_knobs(q))) names += (names.empty() ? "" : " ") + std::string(quality);
    return names;
  };

  // Oscillator method: one actuator voice (metal, A 1, B 90 s⁻¹, f 300 Hz) against Eq. 1
  // in long double over 1 s.
  {
    TradeTable t{"oscillator", "Actuator oscillator method (metal: B 90/s, f 300 Hz; 1 s)", "ns per sample",
                 "max abs error vs long double", true, {}, ""};
    const int m = o.quick ? kFs / 10 : kFs;
    std::vector<long double> ref(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) ref[static_cast<std::size_t>(i)] = eq1_ld(1, 90, 300, static_cast<long double>(i) / kFs);
    auto max_err = [&](const std::vector<double>& x) {
      double e = 0;
      for (int i = 0; i < m; ++i) e = std::max(e, std::fabs(x[static_cast<std::size_t>(i)] - static_cast<double>(ref[static_cast<std::size_t>(i)])));
      return e;
    };
    const VibrationParams metal{1.0, 90.0, 300.0};
    std::vector<double> x(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) x[static_cast<std::size_t>(i)] = decaying_sine_unit_seconds(metal, i / double(kFs));
    const double direct_err = max_err(x);
    const double direct_ns = direct_eq1_ns(metal, n, kFs, runs);
    audio::DampedOscillator osc;
    osc.start(1.0, 90.0, 300.0, 0.0, kFs);
    std::fill(x.begin(), x.end(), 0.0);
    osc.add_to(x.data(), m);
    const double rot_err = max_err(x);
    const double rot_ns = rotator_ns(300.0, n, kFs, runs);
    // A float two-pole resonator y[n] = 2r·cos(ω)·y[n−1] − r²·y[n−2] (the classic cheap way).
    auto resonator = [&](int count, double* into) {
      const float r = static_cast<float>(std::exp(-90.0 / kFs)), w = static_cast<float>(2 * std::numbers::pi * 300.0 / kFs);
      const float c = 2 * r * std::cos(w), r2 = r * r;
      float y2 = 0, y1 = r * std::sin(w);  // y[0], y[1]
      into[0] = 0;
      into[1] = y1;
      for (int i = 2; i < count; ++i) {
        const float y = c * y1 - r2 * y2;
        y2 = y1;
        y1 = y;
        into[i] = y;
      }
    };
    resonator(m, x.data());
    const double res_err = max_err(x);
    std::vector<double> res_buf(static_cast<std::size_t>(n));
    const double res_ns = median_ns_per_unit(runs, n, [&] {
      audio::ScopedFlushDenormals ftz;  // as on the audio thread: its decay goes subnormal after ≈1 s
      resonator(n, res_buf.data());
      keep(res_buf[static_cast<std::size_t>(n - 1)]);
    });
    t.points.push_back({"exp + sin per sample (double)", direct_ns, direct_err, "", "Eq. 1 evaluated directly"});
    t.points.push_back({"re-seeded double rotator", rot_ns, rot_err, "fast balanced exact", "the engine's DampedOscillator"});
    t.points.push_back({"float two-pole resonator", res_ns, res_err, "", "not used: error grows as f falls (~1% at 100 Hz); timed with FTZ on"});
    t.note = "The rotator is on the front in every preset: no cheaper method comes near its error.";
    out.trades.push_back(t);
  }

  const std::vector<ModalPreset> library =
      scene.instruments.empty() ? std::vector<ModalPreset>{} : config::load_instruments(scene.instruments_file);
  const ModalPreset* glock = nullptr;
  for (const ModalPreset& p : library)
    if (!glock || p.modes.size() > glock->modes.size()) glock = &p;

  // Modes per bar: the voice with the most modes, C6 struck at 2 m/s, against all modes
  // in long double.
  if (glock) {
    TradeTable t{"modes", "Modes per bar (" + glock->name + ", " + std::to_string(glock->modes.size()) +
                              " modes, C6 at 2 m/s, 0.5 s)",
                 "ns per sample", "max abs error vs all modes, long double", true, {}, ""};
    const int m = o.quick ? 2048 : kFs / 2;
    const double f0 = 1046.5, v = 2.0;
    const std::vector<long double> ref = note_reference(*glock, f0, v, m);
    TextTable spectral{"Spectral error of the note per modes kept (" + glock->name + ")",
                       {"modes", "largest error component, dB re the note's peak"}, {}, ""};
    for (int k = 1; k <= static_cast<int>(glock->modes.size()); ++k) {
      ModalPreset p = *glock;
      p.max_sounding_modes = k;
      audio::ModalBarVoice voice;
      voice.strike(p, f0, v, 0.0, kFs);
      std::vector<double> x(static_cast<std::size_t>(m), 0.0);
      voice.add_to(x.data(), m);
      double err = 0;
      for (int i = 0; i < m; ++i) err = std::max(err, std::fabs(x[static_cast<std::size_t>(i)] - static_cast<double>(ref[static_cast<std::size_t>(i)])));
      const double ns = modal_bar_ns(p, 523.25, n, kFs, runs);
      const std::string presets = presets_where(
          [&](const QualityKnobs& q) { return k == std::min<int>(q.max_modes, static_cast<int>(glock->modes.size())); });
      t.points.push_back({std::to_string(k) + (k == 1 ? " mode" : " modes"), ns, std::max(err, 1e-16), presets, ""});
      const int dft = std::min(m, o.quick ? 512 : 4096);
      spectral.rows.push_back({std::to_string(k), fmt::format("{:.1f}", spectral_error_db(x, ref, dft))});
    }
    t.note = "Leaving out the top modes loses exactly their share; the modes kept are bit-for-bit those of the full note.";
    out.trades.push_back(t);
    out.tables.push_back(spectral);

    // Peers, same run: ratios are the headline.
    TextTable peers{"Synthesis peers, same process, same run (ratios are the headline)",
                    {"voice", "ns per sample", "× ours"}, {}, ""};
    ModalPreset p = *glock;
    const double ours = modal_bar_ns(p, 523.25, n, kFs, runs);
    peers.rows.push_back({"ours: modal bar voice, " + p.name + " (" + std::to_string(p.modes.size()) + " modes)",
                          fmt::format("{:.2f}", ours), "1.00"});
    if (const std::optional<double> ns = stk_modal_bar_ns(n, kFs, runs))
      peers.rows.push_back(
          {"STK ModalBar (4 modes + strike sample)", fmt::format("{:.2f}", *ns), fmt::format("{:.2f}", *ns / ours)});
    else
      out.skipped.push_back("STK ModalBar: not built (install libstk-dev and stk)");
    try {
      const double ns = fluidsynth_ns_per_voice_frame(n, kFs, runs);
      peers.rows.push_back({"FluidSynth, per voice-frame (16 notes, TimGM6mb)", fmt::format("{:.2f}", ns),
                            fmt::format("{:.2f}", ns / ours)});
    } catch (const std::exception& e) {
      out.skipped.push_back(std::string("FluidSynth: ") + e.what());
    }
    out.tables.push_back(peers);

    // Model only what the output can carry: modes at or above 0.45·fs are not simulated.
    TextTable band{"Modes above the output band are not simulated (" + p.name + ", 48 kHz)",
                   {"note", "modes sounding", "ns per sample"}, {}, ""};
    for (double note_hz : {1046.5, 4186.0}) {
      audio::ModalBarVoice high;
      high.strike(p, note_hz, 1.5, 0.0, kFs);
      const int sounding = high.active_modes();
      const double ns = modal_bar_ns(p, note_hz, n, kFs, runs);
      band.rows.push_back({fmt::format("{:.1f} Hz", note_hz),
                           std::to_string(sounding) + " of " + std::to_string(p.modes.size()),
                           fmt::format("{:.2f}", ns)});
    }
    band.note = "A mode at or above 0.45 × the sample rate could only alias; ModalBarVoice leaves it out (the strike "
                "law's sums still count it, so the modes kept are unchanged).";
    out.tables.push_back(band);
  }

  // Block size: the engine's cost per frame with 16 voices sounding, against the worst
  // impact → first sample latency (sample clock, 100 random impact times).
  if (!scene.targets.empty()) {
    TradeTable blocks{"blocks", "Audio block size (engine, 16 voices)", "ns per frame (engine)",
                      "worst impact → first sample, ms", false, {}, ""};
    TradeTable ahead{"schedule", "schedule_ahead_ms at 64-frame blocks", "worst impact → first sample, ms",
                     "jitter, ms", false, {}, ""};
    std::mt19937 rng(7);
    auto latency = [&](int block, double ahead_ms) {
      AppConfig c;
      c.audio.schedule_ahead_ms = ahead_ms;
      return first_sample_latency(scene, c, kFs, block, 0, o.quick ? 10 : 100, rng);
    };
    for (int block : {16, 32, 64, 128, 256, 512, 1024, 2048}) {
      AppConfig c;
      audio::AudioRig rig = audio::make_audio_rig(scene, c, kFs);
      std::vector<float> buf(static_cast<std::size_t>(2 * block));
      const int frames = std::max(n, 4 * block);
      const double ns = median_ns_per_unit(runs, frames, [&] {
        for (int k = 0; k < 16; ++k) {
          Impact i;
          i.target = k % static_cast<int>(scene.targets.size());
          i.material = scene.targets[static_cast<std::size_t>(i.target)].material;
          i.note = scene.targets[static_cast<std::size_t>(i.target)].note;
          i.speed_m_per_s = 1.0;
          i.t_ns = 0;
          rig.engine->post(i);
        }
        for (int f = 0; f < frames; f += block) rig.engine->process(buf.data(), block);
      });
      const FirstSampleLatency l = latency(block, 0.0);
      const std::string presets = presets_where([&](const QualityKnobs& k) { return k.frames_per_buffer == block; });
      blocks.points.push_back({std::to_string(block) + " frames", ns, l.worst_ms, presets, ""});
    }
    blocks.note = "Smaller blocks: more callbacks per second (fixed cost per call), less waiting for the next one.";
    std::vector<double> aheads = {0.0, 1.0, 1.5, 5.0, 10.0, 12.0, 20.0};
    for (const auto& preset : kQualityNames) {
      const double a = quality_knobs(preset.first).schedule_ahead_ms;
      if (std::find(aheads.begin(), aheads.end(), a) == aheads.end()) aheads.push_back(a);
    }
    std::sort(aheads.begin(), aheads.end());
    for (double a : aheads) {
      const FirstSampleLatency l = latency(64, a);
      const std::string presets = presets_where([&](const QualityKnobs& k) { return k.schedule_ahead_ms == a; });
      ahead.points.push_back({fmt::format("{:g} ms", a), l.worst_ms, l.worst_ms - l.best_ms, presets,
                              a > 0 && a < 64.0 / kFs * 1e3 ? "shorter than one block: late strikes" : ""});
    }
    ahead.note = "A constant delay of at least one block makes every strike sound exactly that late (jitter = one sample). Here each impact is posted at its own time (as a 1000 Hz mouse would); the 100 Hz camera reveals a contact up to 10 ms after it happens, so the exact preset takes 12 ms (see the latency budget: with 5 ms, most strikes came late).";
    out.trades.push_back(blocks);
    out.trades.push_back(ahead);
  }
}

}  // namespace mallet::app
