// `mallet audio devices` and `mallet audio test`: the operator's tools to find the
// output device and check the wiring of the speaker and the stick's voice coil.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "audio/audio_setup.hpp"
#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "audio/portaudio_output.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/impact.hpp"
#include "core/time.hpp"

namespace mallet::app {

namespace {

struct AudioTestOptions {
  std::string channel;  // "actuator" or "acoustic"
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::filesystem::path scene;
  double seconds = 1.5;
  int target = 3;  // a wood bar of the shipped scene (G5 on the xylophone)
  double speed_m_per_s = 1.0;
  std::string sample_format = "float32";
};

void print_devices() {
  const std::vector<audio::DeviceInfo> devices = audio::list_output_devices();
  if (devices.empty())
    throw std::runtime_error(
        "no audio output device found (PortAudio sees none: is a sound card present and ALSA configured?)");
  std::printf("%5s  %-40s %-10s %8s %10s %12s\n", "index", "name", "host API", "channels", "rate (Hz)",
              "latency (ms)");
  for (const audio::DeviceInfo& d : devices)
    std::printf("%5d  %-40s %-10s %8d %10.0f %12.1f%s\n", d.index, d.name.c_str(), d.host_api.c_str(),
                d.max_output_channels, d.default_sample_rate_hz, d.default_low_latency_s * 1e3,
                d.is_default ? "  (default)" : "");
  std::printf("Select one with [audio].device in the settings file: its index or a part of its name.\n");
}

void run_audio_test(const AudioTestOptions& o) {
  const AppConfig config = command_settings(o.config, o.config_dir, "audio test");
  const Scene scene = config::load_scene(o.scene);
  if (o.target < 0 || static_cast<std::size_t>(o.target) >= scene.targets.size())
    throw CLI::ValidationError("--target", "no bar " + std::to_string(o.target) + " in " + scene.file + " (0.." +
                                               std::to_string(scene.targets.size() - 1) +
                                               "; see `mallet scene describe`)");
  const bool acoustic = o.channel == "acoustic";

  // The same engine the kiosk runs (presets from the scene's instruments_file, each
  // instrument's `voice`); the other channel is silenced so only the one under test sounds.
  audio::AudioRig rig = audio::make_audio_rig(scene, config, config.audio.sample_rate_hz, /*acoustic_enabled=*/acoustic);
  if (acoustic) rig.engine->set_actuator_gain(0.0);

  audio::PortAudioOutput::Options output_options;
  output_options.format = o.sample_format == "int16" ? audio::StreamFormat::int16 : audio::StreamFormat::float32;
  audio::PortAudioOutput output(*rig.engine, config.audio, output_options);
  const audio::DeviceInfo device = output.device();
  std::printf("device: %d \"%s\" (%s), %d ch at %.0f Hz, %s\n", device.index, device.name.c_str(),
              device.host_api.c_str(), config.audio.routing.channels, output.sample_rate_hz(),
              o.sample_format.c_str());
  std::printf("output latency: %.2f ms (PortAudio's figure for this stream)\n", output.output_latency_s() * 1e3);
  std::fflush(stdout);

  output.start();
  const Target& bar = scene.targets[static_cast<std::size_t>(o.target)];
  Impact impact;
  impact.t_ns = monotonic_now() + 50'000'000;  // 50 ms from now
  impact.target = bar.id;
  impact.material = bar.material;
  impact.note = bar.note;
  impact.speed_m_per_s = o.speed_m_per_s;
  impact.x_m = 0.5 * (bar.x_min + bar.x_max);
  if (!rig.engine->post(impact)) throw std::runtime_error("audio: the engine's event ring is full");
  std::this_thread::sleep_for(std::chrono::duration<double>(o.seconds));
  const bool device_ok = output.device_ok();
  output.stop();

  const Material& m = scene.material_of(bar);
  const AudioRouting& r = config.audio.routing;
  if (acoustic) {
    std::printf("played: bar %d (%s, %s, MIDI %d, %.1f Hz) at %.2f m/s, the note (%s) on channel %d (acoustic)\n",
                bar.id, bar.instrument.c_str(), m.name.c_str(), bar.note, bar.frequency_hz, o.speed_m_per_s,
                config.audio.acoustic == AcousticRoute::midi ? "FluidSynth" : "modal synthesis", r.acoustic);
  } else {
    const VibrationParams& a = m.actuator;
    std::printf(
        "played: bar %d (%s, %s) at %.2f m/s, Eq. 1 on channel %d (actuator): "
        "%.3f·e^(-%.1f·t)·sin(2π·%.1f·t) of full scale\n",
        bar.id, bar.instrument.c_str(), m.name.c_str(), o.speed_m_per_s, r.actuator,
        config.actuator.gain * a.amplitude * o.speed_m_per_s, a.decay_per_s, a.freq_hz);
  }
  if (r.acoustic == r.actuator) std::printf("note: [audio.routing] mixes both signals on channel %d\n", r.acoustic);
  const audio::OutputCounters c = output.counters();
  std::printf("%llu callbacks, %llu frames, %llu underrun(s)%s\n", static_cast<unsigned long long>(c.callbacks),
              static_cast<unsigned long long>(c.frames), static_cast<unsigned long long>(c.xruns),
              c.device_losses ? ", the device was lost during the test" : "");
  if (!device_ok)
    throw std::runtime_error("audio: the output device was lost during the test and did not come back");
}

}  // namespace

void register_audio(CLI::App& app) {
  CLI::App* audio = app.add_subcommand("audio", "Audio output: list devices, play a test strike");
  audio->require_subcommand(1);

  CLI::App* devices = audio->add_subcommand("devices", "List the audio outputs PortAudio sees (ALSA)");
  devices->footer(R"(Columns: PortAudio index, name, host API, output channels, default sample rate and
PortAudio's default low output latency. Set [audio].device to an index or a part of a
name. With no output device it says so and exits 1.)");
  devices->callback([] { print_devices(); });

  auto o = std::make_shared<AudioTestOptions>();
  o->scene = default_scene();
  CLI::App* test = audio->add_subcommand("test", "Play one test strike on one channel to check the wiring");
  test->footer(R"(Opens the configured output ([audio] in --config), plays one strike 50 ms after the start
and keeps the stream running for --seconds:
  --channel actuator  Eq. 1 of the bar's material on [audio.routing].actuator (default 1),
                      the speaker channel silent — the stick's voice coil should buzz
  --channel acoustic  the bar's note on [audio.routing].acoustic (default 0), the actuator
                      silent — the speaker should ring
Prints the device, the output latency PortAudio reports and what was played.
Bad input exits 2; a device that cannot be opened exits 1.)");
  test->add_option("--channel", o->channel, "Which signal to play")
      ->required()
      ->check(CLI::IsMember({"actuator", "acoustic"}));
  add_settings_options(*test, o->config, o->config_dir);
  test->add_option("--scene", o->scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  test->add_option("--seconds", o->seconds, "How long the stream runs")
      ->capture_default_str()
      ->check(positive_at_most(60.0));
  test->add_option("--target", o->target, "Bar id to strike (`mallet scene describe`; 3 = a wood bar)")
      ->capture_default_str();
  test->add_option("--speed", o->speed_m_per_s, "Impact speed in m/s")
      ->capture_default_str()
      ->check(positive_at_most(10.0));
  test->add_option("--sample-format", o->sample_format,
                   "Device sample type; int16 for outputs that take only 16-bit (e.g. ALSA's file plugin)")
      ->check(CLI::IsMember({"float32", "int16"}))
      ->capture_default_str();
  test->callback([o] { run_audio_test(*o); });
}

}  // namespace mallet::app
