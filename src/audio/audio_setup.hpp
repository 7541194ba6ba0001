#pragma once
// Builds the audio engine for a scene and a configuration, the same way for the kiosk,
// `mallet simulate` (offline, into a WAV) and `mallet audio test`.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "audio/engine.hpp"
#include "audio/fluidsynth_route.hpp"
#include "audio/stream_capture.hpp"
#include "core/actuator_eq_file.hpp"
#include "core/app_config.hpp"
#include "core/scene.hpp"

namespace mallet::audio {

class PortAudioOutput;

struct AudioRig {
  std::unique_ptr<FluidSynthRoute> midi;  //!< only for the midi route
  std::unique_ptr<AudioEngine> engine;
  std::optional<ActuatorEq> actuator_eq;  //!< the actuator calibration in force, if any
};

//! The actuator calibration the engine applies: `path` (the state folder's
//! actuator_eq.toml) when [actuator] equalize is true and the file exists, reads, and was
//! made at `sample_rate_hz`. Otherwise none, with one journal line saying why for a file
//! that is there but cannot be used (the kiosk plays on without it).
std::optional<ActuatorEq> actuator_eq_in_force(const AppConfig& config, int sample_rate_hz,
                                               const std::filesystem::path& path);

//! Loads the scene's acoustic presets (Scene::instruments_file; each instrument's
//! `voice`), and for the midi route the soundfont. Bad files → FileError (exit 2);
//! a missing soundfont → std::runtime_error naming the Debian package.
AudioRig make_audio_rig(const Scene& scene, const AppConfig& config, int sample_rate_hz,
                        bool acoustic_enabled = true);

//! Opens and starts the configured audio device for `engine`. Without one (no sound card,
//! a device that fails to open) it logs why on stderr and returns null: the caller runs
//! silent. `status` becomes "audio: NAME, LATENCY ms" or "audio: none (running silent): WHY".
//! `capture`: the stream also records these inputs (PortAudioOutput::Options::capture).
std::unique_ptr<PortAudioOutput> start_output(AudioEngine& engine, const AudioConfig& config, std::string& status,
                                              const std::optional<CaptureSpec>& capture = std::nullopt);

}  // namespace mallet::audio
