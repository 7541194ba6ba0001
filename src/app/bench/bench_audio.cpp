// `mallet bench audio`: what one voice costs, what the engine costs with many voices,
// and how late an impact reaches the output — measured in one run on this machine, with
// the peers (STK's ModalBar, FluidSynth) side by side. A program that prints a table;
// no test times anything.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "audio/audio_setup.hpp"
#include "app/bench/bench_commands.hpp"
#include "app/bench/first_sample_latency.hpp"
#include "app/bench/voice_cost.hpp"
#include "core/data_paths.hpp"
#include "audio/damped_oscillator.hpp"
#include "audio/fluidsynth_route.hpp"
#include "audio/modal_bar.hpp"
#include "core/config/instruments_config.hpp"
#include "core/config/scene_config.hpp"
#include "core/vibration.hpp"


namespace mallet::app {

namespace {

struct VoiceRow {
  std::string what;
  double ns = 0;
  std::string note;
};

void print_rows(const char* title, const char* unit, const std::vector<VoiceRow>& rows) {
  std::printf("\n%s\n", title);
  std::printf("| %-44s | %12s | %s\n", "", unit, "note");
  std::printf("|%s|%s|%s\n", std::string(46, '-').c_str(), std::string(14, '-').c_str(), "------");
  for (const VoiceRow& r : rows) std::printf("| %-44s | %12.2f | %s\n", r.what.c_str(), r.ns, r.note.c_str());
}

}  // namespace

void run_bench_audio(const std::filesystem::path& scene_path, int seconds_of_audio) {
  const Scene scene = config::load_scene(scene_path);
  const std::vector<ModalPreset> presets = config::load_instruments(scene.instruments_file);
  const int fs = 48000;
  const int n = fs * seconds_of_audio;
  const int runs = 7;
  std::vector<VoiceRow> voice;

  // Eq. 1 evaluated directly (exp + sin per sample): the exact reference.
  const VibrationParams metal{2.0, 90.0, 300.0};
  voice.push_back({"Eq. 1 direct (exp+sin per sample, reference)", direct_eq1_ns(metal, n, fs, runs), "exact"});
  audio::DampedOscillator osc;
  double osc_error = 0;
  osc.start(2.0, 90.0, 300.0, 0.0, fs);
  for (int i = 0; i < fs; ++i)
    osc_error = std::max(osc_error, std::fabs(osc.tick() - 2.0 * decaying_sine_unit_seconds(metal, i / double(fs))));
  voice.push_back({"actuator voice (re-seeded double rotator)", rotator_ns(300.0, n, fs, runs),
                   "max |error| vs exact over 1 s: " + std::to_string(osc_error)});
  for (const ModalPreset& p : presets)
    voice.push_back({"modal bar voice: " + p.name + " (" + std::to_string(p.modes.size()) + " modes)",
                     modal_bar_ns(p, 523.25, n, fs, runs), ""});
  if (const std::optional<double> stk = stk_modal_bar_ns(n, fs, runs))
    voice.push_back({"peer: STK ModalBar (4 modes + strike sample)", *stk, "libstk "});
  else
    voice.push_back({"peer: STK ModalBar", 0, "not built (install libstk-dev and stk)"});
  voice.push_back(
      {"peer: FluidSynth (16 notes, per voice-frame)", fluidsynth_ns_per_voice_frame(n, fs, runs), "TimGM6mb"});
  print_rows("Cost of one voice at 48 kHz (median of 7 runs)", "ns/sample", voice);

  // The engine with many voices: the share of one core a 64-frame callback takes.
  std::vector<VoiceRow> engine_rows;
  for (int voices : {16, 64, 256, 512}) {
    AppConfig config;
    config.audio.max_voices = voices;
    audio::AudioRig rig = audio::make_audio_rig(scene, config, fs);
    std::vector<float> out(2 * 64);
    const int blocks = n / 64;
    const double ns_per_block = median_ns_per_unit(runs, blocks, [&] {
      for (int b = 0; b < blocks; ++b) {
        if (b % 8 == 0)  // keep the pool full: a new strike every 8 blocks steals the quietest
          for (int k = 0; k < voices; ++k) {
            Impact i;
            i.t_ns = 0;
            i.target = k % static_cast<int>(scene.targets.size());
            i.material = scene.targets[static_cast<std::size_t>(i.target)].material;
            i.note = scene.targets[static_cast<std::size_t>(i.target)].note;
            i.speed_m_per_s = 1.0;
            if (b == 0 || k == b % voices) rig.engine->post(i);
          }
        rig.engine->process(out.data(), 64);
      }
    });
    const double block_ns = 64.0 / fs * 1e9;
    engine_rows.push_back({std::to_string(voices) + " voices, 64-frame blocks", 100.0 * ns_per_block / block_ns,
                           std::to_string(ns_per_block / (64.0 * voices)) + " ns per voice-sample; active " +
                               std::to_string(rig.engine->counters().active_voices)});
  }
  print_rows("Engine load (modal route): share of one core at 48 kHz", "% of core", engine_rows);

  // Impact → first sample: where in the output stream an impact lands, relative to its
  // own time, for random impact times (sample arithmetic: exact, not wall time).
  std::vector<VoiceRow> latency_rows;
  std::mt19937 rng(1);
  for (int block : {16, 64, 256}) {
    for (double ahead : {0.0, 5.0}) {
      AppConfig config;
      config.audio.schedule_ahead_ms = ahead;
      const FirstSampleLatency l = first_sample_latency(scene, config, fs, block, 3, 200, rng);
      latency_rows.push_back({std::to_string(block) + "-frame blocks, schedule_ahead_ms = " + std::to_string(int(ahead)),
                              l.worst_ms, "min " + std::to_string(l.best_ms) + " ms, jitter " +
                                              std::to_string(l.worst_ms - l.best_ms) +
                                              " ms (+ the device's output latency)"});
    }
  }
  print_rows("Impact → first output sample, 200 random impact times", "max ms", latency_rows);
}

void add_bench_audio(CLI::App& bench) {
  auto scene = std::make_shared<std::filesystem::path>(default_scene());
  auto seconds = std::make_shared<int>(2);
  CLI::App* audio_cmd = bench.add_subcommand("audio", "Cost per voice, engine load and impact-to-sample latency");
  audio_cmd->add_option("--scene", *scene, "Scene file")->capture_default_str();
  audio_cmd->add_option("--seconds", *seconds, "Seconds of audio rendered per measurement")->capture_default_str();
  audio_cmd->callback([scene, seconds] { run_bench_audio(*scene, std::max(1, *seconds)); });
}

}  // namespace mallet::app
