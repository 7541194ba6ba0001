#pragma once
// What the kiosk's output (audio/portaudio_output.hpp) and the actuator's measurement
// (audio/duplex_measurement.hpp) share of PortAudio: the process-wide lock (PortAudio is not
// thread-safe), an initialised session that keeps ALSA's and JACK's probing quiet, and the
// devices looked up by index or by a part of their name.
#include <mutex>
#include <string>
#include <vector>

#include "audio/portaudio_output.hpp"

namespace mallet::audio {

//! PortAudio is not thread-safe: every call outside an audio callback holds this.
std::mutex& pa_mutex();

//! PortAudio's text for an error code (with the host's own text when it has one).
std::string error_text(int pa_error);

//! Pa_Initialize for its lifetime (Pa_Terminate after), with ALSA's and JACK's diagnostics
//! dropped while it probes (MALLET_AUDIO_DEBUG=1 keeps them). Throws std::runtime_error.
class PaSession {
 public:
  PaSession();
  ~PaSession();
  PaSession(const PaSession&) = delete;
  PaSession& operator=(const PaSession&) = delete;
};

// Each below with PortAudio initialised and pa_mutex() held.
DeviceInfo describe(int index);
std::vector<DeviceInfo> outputs_locked();
std::vector<DeviceInfo> inputs_locked();
//! "output devices: 0 "NAME"; ..." for the messages.
std::string known_devices(const std::vector<DeviceInfo>& outputs);
//! [audio] device → the output devices to try, in order: empty = the default (after ALSA's
//! dmix itself where the default leads to it), all digits = index, else a case-insensitive
//! part of the name (an exact name wins). Throws std::runtime_error naming those there are.
std::vector<DeviceInfo> resolve_locked(const std::string& spec);
//! The same for an input device (empty = the default input). Throws NoInput
//! (duplex_measurement.hpp), naming the input devices there are.
DeviceInfo resolve_input_locked(const std::string& spec);

}  // namespace mallet::audio
