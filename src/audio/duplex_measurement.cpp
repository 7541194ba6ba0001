#include "audio/duplex_measurement.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <portaudio.h>

#include "audio/portaudio_session.hpp"

namespace mallet::audio {

namespace {

struct Transfer {
  std::span<const float> signal;
  int out_channels = 0, out_channel = 0, in_channels = 0;
  std::vector<float> recorded;  // interleaved in_channels, preallocated
  std::size_t frames = 0;       // to play and record in all
  std::atomic<std::size_t> done{0};
  std::atomic<unsigned long> xruns{0};
};

int callback(const void* input, void* output, unsigned long frames, const PaStreamCallbackTimeInfo*,
             PaStreamCallbackFlags flags, void* user) {
  auto& t = *static_cast<Transfer*>(user);
  if (flags & (paInputOverflow | paOutputUnderflow | paInputUnderflow | paOutputOverflow))
    t.xruns.fetch_add(1, std::memory_order_relaxed);
  const std::size_t at = t.done.load(std::memory_order_relaxed);
  auto* out = static_cast<float*>(output);
  const auto* in = static_cast<const float*>(input);
  for (unsigned long i = 0; i < frames; ++i) {
    const std::size_t n = at + i;
    for (int c = 0; c < t.out_channels; ++c) out[i * static_cast<unsigned long>(t.out_channels) + static_cast<unsigned long>(c)] = 0.0f;
    if (n < t.signal.size()) out[i * static_cast<unsigned long>(t.out_channels) + static_cast<unsigned long>(t.out_channel)] = t.signal[n];
    if (n < t.frames && in)
      for (int c = 0; c < t.in_channels; ++c)
        t.recorded[n * static_cast<std::size_t>(t.in_channels) + static_cast<std::size_t>(c)] =
            in[i * static_cast<unsigned long>(t.in_channels) + static_cast<unsigned long>(c)];
  }
  t.done.store(at + frames, std::memory_order_release);
  return at + frames >= t.frames ? paComplete : paContinue;
}

}  // namespace

DuplexRecording play_and_record(const DuplexRequest& r, std::span<const float> signal) {
  if (r.input_channels.empty()) throw std::invalid_argument("nothing to record: no input channel asked for");
  if (r.output_channel < 0 || r.output_channel >= r.output_channels)
    throw std::invalid_argument(fmt::format("output channel {} is not one of the stream's {}", r.output_channel + 1, r.output_channels));
  const int in_channels = *std::max_element(r.input_channels.begin(), r.input_channels.end()) + 1;
  if (*std::min_element(r.input_channels.begin(), r.input_channels.end()) < 0)
    throw std::invalid_argument("input channels are counted from 1");

  std::lock_guard lock(pa_mutex());
  PaSession session;
  const DeviceInfo out_device = resolve_locked(r.output_device).front();
  const DeviceInfo in_device = resolve_input_locked(r.input_device);
  if (in_device.max_input_channels < in_channels)
    throw NoInput(fmt::format("this sound card has no input: \"{}\" records {} channel(s), channel {} was asked for",
                                         in_device.name, in_device.max_input_channels, in_channels));
  if (out_device.max_output_channels < r.output_channels)
    throw std::runtime_error(fmt::format("audio: \"{}\" has {} output channel(s), {} are needed", out_device.name,
                                         out_device.max_output_channels, r.output_channels));

  Transfer t;
  t.signal = signal;
  t.out_channels = r.output_channels;
  t.out_channel = r.output_channel;
  t.in_channels = in_channels;
  t.frames = signal.size() + static_cast<std::size_t>(std::llround(r.tail_s * r.sample_rate_hz));
  t.recorded.assign(t.frames * static_cast<std::size_t>(in_channels), 0.0f);

  PaStreamParameters in{};
  in.device = in_device.index;
  in.channelCount = in_channels;
  in.sampleFormat = paFloat32;
  in.suggestedLatency = in_device.default_low_input_latency_s;
  PaStreamParameters out{};
  out.device = out_device.index;
  out.channelCount = r.output_channels;
  out.sampleFormat = paFloat32;
  out.suggestedLatency = std::max(out_device.default_low_latency_s, 0.010);
  PaStream* stream = nullptr;
  if (const PaError e = Pa_OpenStream(&stream, &in, &out, r.sample_rate_hz, paFramesPerBufferUnspecified, paClipOff,
                                      &callback, &t);
      e != paNoError)
    throw std::runtime_error(fmt::format("audio: cannot open \"{}\" (out) with \"{}\" (in) at {} Hz: {}", out_device.name,
                                         in_device.name, r.sample_rate_hz, error_text(e)));
  DuplexRecording rec;
  rec.sample_rate_hz = r.sample_rate_hz;
  rec.output_name = out_device.name;
  rec.input_name = in_device.name;
  if (const PaStreamInfo* info = Pa_GetStreamInfo(stream)) {
    rec.output_latency_s = info->outputLatency;
    rec.input_latency_s = info->inputLatency;
  }
  if (const PaError e = Pa_StartStream(stream); e != paNoError) {
    Pa_CloseStream(stream);
    throw std::runtime_error("audio: cannot start the measurement stream: " + error_text(e));
  }
  // Wait for the last frame, allowing for a slow start; a stream that stops delivering for
  // two seconds is lost.
  std::size_t seen = 0;
  auto last_progress = std::chrono::steady_clock::now();
  while (t.done.load(std::memory_order_acquire) < t.frames) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::size_t now = t.done.load(std::memory_order_acquire);
    if (now != seen) {
      seen = now;
      last_progress = std::chrono::steady_clock::now();
    } else if (std::chrono::steady_clock::now() - last_progress > std::chrono::seconds(2) || Pa_IsStreamActive(stream) != 1) {
      if (t.done.load(std::memory_order_acquire) >= t.frames) break;
      Pa_AbortStream(stream);
      Pa_CloseStream(stream);
      throw std::runtime_error(fmt::format("audio: the measurement stream stopped after {} of {} frames", now, t.frames));
    }
  }
  Pa_StopStream(stream);
  Pa_CloseStream(stream);
  rec.xruns = t.xruns.load();
  rec.channels.resize(r.input_channels.size());
  for (std::size_t k = 0; k < r.input_channels.size(); ++k) {
    auto& ch = rec.channels[k];
    ch.resize(t.frames);
    for (std::size_t n = 0; n < t.frames; ++n)
      ch[n] = t.recorded[n * static_cast<std::size_t>(in_channels) + static_cast<std::size_t>(r.input_channels[k])];
  }
  return rec;
}

}  // namespace mallet::audio
