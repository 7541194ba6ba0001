#include "audio/audio_setup.hpp"

#include <cstdio>
#include <exception>

#include <fmt/format.h>

#include "audio/portaudio_output.hpp"
#include "core/config/instruments_config.hpp"
#include "core/data_paths.hpp"
#include "core/file_error.hpp"
#include "core/journal.hpp"
#include "core/named.hpp"

namespace mallet::audio {

std::optional<ActuatorEq> actuator_eq_in_force(const AppConfig& config, int sample_rate_hz,
                                               const std::filesystem::path& path) {
  std::error_code ec;
  if (!config.actuator.equalize || !std::filesystem::exists(path, ec)) return std::nullopt;
  try {
    ActuatorEq eq = load_actuator_eq(path);
    if (eq.sample_rate_hz != sample_rate_hz) {
      journal::warning("{}: measured at {} Hz, the audio runs at {} Hz: the actuator is not equalised "
                       "(mallet calibrate actuator again)",
                       path.string(), eq.sample_rate_hz, sample_rate_hz);
      return std::nullopt;
    }
    return eq;
  } catch (const std::exception& e) {
    journal::warning("{}; the actuator is not equalised", e.what());
    return std::nullopt;
  }
}

AudioRig make_audio_rig(const Scene& scene, const AppConfig& config, int sample_rate_hz, bool acoustic_enabled) {
  // A scene without instruments (the texture) needs no acoustic presets at all.
  const std::vector<ModalPreset> library =
      scene.instruments.empty() ? std::vector<ModalPreset>{} : config::load_instruments(scene.instruments_file);
  std::vector<ModalPreset> presets;
  std::vector<int> programs;
  for (const Instrument& inst : scene.instruments) {
    const ModalPreset* found = find_named(library, inst.voice);
    if (!found)
      throw FileError(scene.file, 0, 0, "instrument " + inst.name + ": no voice \"" + inst.voice + "\" in " +
                                            scene.instruments_file + " (known: " + names_of(library) + ")");
    presets.push_back(*found);
    presets.back().max_sounding_modes = config.audio.max_modes;
    programs.push_back(inst.midi_program);
  }
  EngineSettings s;
  s.sample_rate_hz = sample_rate_hz;
  s.routing = config.audio.routing;
  s.actuator = config.actuator;
  s.schedule_ahead_ms = config.audio.schedule_ahead_ms;
  s.max_voices = config.audio.max_voices;
  s.acoustic_volume = config.audio.volume;
  s.acoustic_enabled = acoustic_enabled;
  AudioRig rig;
  rig.actuator_eq = actuator_eq_in_force(config, sample_rate_hz, actuator_eq_path());
  if (rig.actuator_eq) {
    s.actuator_eq = rig.actuator_eq->taps;
    s.eq_alignment_samples = rig.actuator_eq->alignment_samples();
  }
  if (config.audio.acoustic == AcousticRoute::midi)
    rig.midi = std::make_unique<FluidSynthRoute>(config.audio.soundfont, sample_rate_hz, programs);
  try {
    rig.engine = std::make_unique<AudioEngine>(scene, std::move(presets), s);
  } catch (const std::invalid_argument& e) {
    throw FileError(scene.file, 0, 0, e.what());
  }
  if (rig.midi) rig.engine->set_external_acoustic(rig.midi.get());
  return rig;
}

std::unique_ptr<PortAudioOutput> start_output(AudioEngine& engine, const AudioConfig& config, std::string& status,
                                              const std::optional<CaptureSpec>& capture) {
  try {
    PortAudioOutput::Options options;
    options.capture = capture;
    auto output = std::make_unique<PortAudioOutput>(engine, config, options);
    output->start();
    status = fmt::format("audio: {}, {:.1f} ms", output->device().name.c_str(),
                         output->output_latency_s() * 1e3);
    return output;
  } catch (const std::exception& e) {  // the screen still plays, silently
    journal::error("{}; running without sound", e.what());
    std::string why = e.what();  // why, as `mallet doctor` says it (the line's head once)
    if (why.rfind("audio: ", 0) == 0) why.erase(0, 7);
    status = "audio: none (running silent): " + why;
    return nullptr;
  }
}

}  // namespace mallet::audio
