#include "audio/portaudio_session.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>

#include <dlfcn.h>
#include <portaudio.h>

#include "audio/duplex_measurement.hpp"
#if __has_include(<alsa/error.h>)
#include <alsa/asoundlib.h>  // only snd_lib_error_set_handler; libasound is in portaudio-2.0's Libs
#define MALLET_HAVE_ALSA_ERROR_HANDLER 1
#endif

namespace mallet::audio {

namespace {

#ifdef MALLET_HAVE_ALSA_ERROR_HANDLER
void ignore_alsa(const char*, int, const char*, int, const char*, ...) {}
#endif
void ignore_jack(const char*) {}

// Pa_Initialize probes every PCM in ALSA's configuration and tries to reach a JACK
// server; on a kiosk with one card (or none, in CI) that prints dozens of lines about
// devices that do not exist, and the supervisor re-initialises on every reopen attempt.
// Those diagnostics are dropped while probing (MALLET_AUDIO_DEBUG=1 keeps them). What
// matters is reported by PortAudio's own error codes. libjack is not linked by us: its
// handler is set only if PortAudio loaded it.
class QuietProbe {
 public:
  QuietProbe() : active_(!debug()) {
    if (!active_) return;
#ifdef MALLET_HAVE_ALSA_ERROR_HANDLER
    snd_lib_error_set_handler(&ignore_alsa);
#endif
    set_jack(&ignore_jack);
  }
  ~QuietProbe() {
    if (!active_) return;
#ifdef MALLET_HAVE_ALSA_ERROR_HANDLER
    snd_lib_error_set_handler(nullptr);  // back to ALSA's default (stderr)
#endif
    // JACK keeps ours: its later messages (a server that vanished) are as noisy and the
    // stream's state tells the supervisor the same thing.
  }
  QuietProbe(const QuietProbe&) = delete;
  QuietProbe& operator=(const QuietProbe&) = delete;

 private:
  static bool debug() {
    const char* env = std::getenv("MALLET_AUDIO_DEBUG");
    return env && *env && std::string(env) != "0";
  }
  static void set_jack(void (*handler)(const char*)) {
    using Setter = void (*)(void (*)(const char*));
    for (const char* name : {"jack_set_error_function", "jack_set_info_function"})
      if (void* f = dlsym(RTLD_DEFAULT, name)) reinterpret_cast<Setter>(f)(handler);
  }
  bool active_;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::mutex& pa_mutex() {
  static std::mutex m;
  return m;
}

std::string error_text(int e) {
  std::string text = Pa_GetErrorText(e);
  if (e == paUnanticipatedHostError) {
    const PaHostErrorInfo* host = Pa_GetLastHostErrorInfo();
    if (host && host->errorText && *host->errorText) text += std::string(" (") + host->errorText + ")";
  }
  return text;
}

PaSession::PaSession() {
  QuietProbe quiet;
  if (const PaError e = Pa_Initialize(); e != paNoError)
    throw std::runtime_error("audio: cannot initialise PortAudio: " + error_text(e));
}

PaSession::~PaSession() { Pa_Terminate(); }

// With PortAudio initialised and pa_mutex() held.
DeviceInfo describe(int index) {
  const PaDeviceInfo* d = Pa_GetDeviceInfo(index);
  DeviceInfo info;
  info.index = index;
  if (!d) return info;
  info.name = d->name ? d->name : "";
  if (const PaHostApiInfo* api = Pa_GetHostApiInfo(d->hostApi); api && api->name) info.host_api = api->name;
  info.max_output_channels = d->maxOutputChannels;
  info.max_input_channels = d->maxInputChannels;
  info.default_low_input_latency_s = d->defaultLowInputLatency;
  info.default_sample_rate_hz = d->defaultSampleRate;
  info.default_low_latency_s = d->defaultLowOutputLatency;
  info.is_default = index == Pa_GetDefaultOutputDevice();
  info.is_default_input = index == Pa_GetDefaultInputDevice();
  return info;
}

namespace {

// Every device with channels in that direction.
std::vector<DeviceInfo> devices_locked(bool inputs) {
  std::vector<DeviceInfo> out;
  const PaDeviceIndex count = Pa_GetDeviceCount();
  for (PaDeviceIndex i = 0; i < count; ++i) {
    const PaDeviceInfo* d = Pa_GetDeviceInfo(i);
    if (d && (inputs ? d->maxInputChannels : d->maxOutputChannels) > 0) out.push_back(describe(i));
  }
  return out;
}

}  // namespace

std::vector<DeviceInfo> outputs_locked() { return devices_locked(false); }

std::string known_devices(const std::vector<DeviceInfo>& outputs) {
  if (outputs.empty()) return "PortAudio sees no output device at all";
  std::string text = "output devices:";
  for (const DeviceInfo& d : outputs) text += " " + std::to_string(d.index) + " \"" + d.name + "\";";
  text.pop_back();
  return text + " (see `mallet audio devices`)";
}

// config.device → the devices to try, in order: empty = the default (after ALSA's dmix
// itself where the default leads to it: see UNDERRUNS in the header), all digits = index,
// else a case-insensitive part of the name (an exact name wins over a part of a longer one).
std::vector<DeviceInfo> resolve_locked(const std::string& spec) {
  const std::vector<DeviceInfo> outputs = outputs_locked();
  if (spec.empty()) {
    if (outputs.empty())
      throw std::runtime_error(
          "audio: no audio output device found (PortAudio sees none: no sound card, or ALSA is not configured)");
    std::vector<DeviceInfo> order = default_output_order(outputs);
    if (order.empty())
      throw std::runtime_error("audio: there is no default output device; set [audio].device to one of the " +
                               known_devices(outputs));
    return order;
  }
  if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
    for (const DeviceInfo& d : outputs)
      if (spec.size() < 10 && d.index == std::stoi(spec)) return {d};
    throw std::runtime_error("audio: device " + spec + " is not an output device; " + known_devices(outputs));
  }
  const std::string want = lower(spec);
  for (const DeviceInfo& d : outputs)
    if (lower(d.name) == want) return {d};
  for (const DeviceInfo& d : outputs)
    if (lower(d.name).find(want) != std::string::npos) return {d};
  throw std::runtime_error("audio: no output device matches \"" + spec + "\"; " + known_devices(outputs));
}

std::vector<DeviceInfo> inputs_locked() { return devices_locked(true); }

DeviceInfo resolve_input_locked(const std::string& spec) {
  const std::vector<DeviceInfo> inputs = inputs_locked();
  std::string known = "input devices:";
  for (const DeviceInfo& d : inputs) known += " " + std::to_string(d.index) + " \"" + d.name + "\";";
  if (inputs.empty()) known = "PortAudio sees no input device at all";
  if (spec.empty()) {
    for (const DeviceInfo& d : inputs)
      if (d.is_default_input) return d;
    throw NoInput("this sound card has no input: there is no default input device (" + known + ")");
  }
  if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
    for (const DeviceInfo& d : inputs)
      if (spec.size() < 10 && d.index == std::stoi(spec)) return d;
    throw NoInput("this sound card has no input: device " + spec + " records nothing (" + known + ")");
  }
  const std::string want = lower(spec);
  for (const DeviceInfo& d : inputs)
    if (lower(d.name) == want) return d;
  for (const DeviceInfo& d : inputs)
    if (lower(d.name).find(want) != std::string::npos) return d;
  throw NoInput("this sound card has no input: no input device matches \"" + spec + "\" (" + known + ")");
}

}  // namespace mallet::audio
