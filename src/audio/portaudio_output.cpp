#include "audio/portaudio_output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include <portaudio.h>

#include "audio/duplex_measurement.hpp"
#include "audio/portaudio_session.hpp"
#include "core/journal.hpp"
#include "core/sample_clock.hpp"
#include "core/time.hpp"

namespace mallet::audio {

namespace {

constexpr int kScratchFrames = 4096;  // int16 conversion and silent rendering, in pieces

}  // namespace

class PortAudioOutput::Session : public PaSession {};

struct PortAudioOutput::Trampoline {
  static int callback(const void* input, void* output, unsigned long frames, const PaStreamCallbackTimeInfo*,
                      PaStreamCallbackFlags flags, void* self) {
    return static_cast<PortAudioOutput*>(self)->render(input, output, frames, flags);
  }
  static void finished(void* self) {
    static_cast<PortAudioOutput*>(self)->stream_finished_.store(true, std::memory_order_relaxed);
  }
};

std::vector<DeviceInfo> list_output_devices() {
  std::lock_guard lock(pa_mutex());
  PaSession session;
  return outputs_locked();
}

PortAudioOutput::PortAudioOutput(AudioEngine& engine, const AudioConfig& config, Options options)
    : engine_(engine),
      config_(config),
      options_(options),
      channels_(engine.settings().routing.channels),
      sample_rate_(engine.settings().sample_rate_hz) {
  if (config.sample_rate_hz != sample_rate_ || config.routing.channels != channels_)
    throw std::invalid_argument("audio: the engine and [audio] disagree on sample rate or channel count");
  if (config.frames_per_buffer < 0 || config.frames_per_buffer > 8192)
    throw std::invalid_argument("audio: frames_per_buffer must be in [0, 8192] (0 = PortAudio chooses)");
  if (!(config.suggested_latency_ms >= 0 && config.suggested_latency_ms <= 2000))
    throw std::invalid_argument("audio: suggested_latency_ms must be in [0, 2000] (0 = the device's default)");
  if (!(config.min_latency_ms >= 0 && config.min_latency_ms <= config.max_latency_ms && config.max_latency_ms <= 2000))
    throw std::invalid_argument("audio: need 0 <= min_latency_ms <= max_latency_ms <= 2000");
  if (config.grow_after_underruns < 0 || !(config.underrun_window_ms > 0))
    throw std::invalid_argument("audio: grow_after_underruns must be >= 0 and underrun_window_ms > 0");
  scratch_.resize(static_cast<std::size_t>(kScratchFrames) * static_cast<std::size_t>(channels_));
  if (options_.capture)
    capture_ = std::make_unique<StreamCapture>(sample_rate_, options_.capture->input_channels, options_.capture->seconds);
  std::lock_guard lock(pa_mutex());
  session_ = std::make_unique<Session>();
  open_locked();
}

PortAudioOutput::~PortAudioOutput() {
  stop();
  std::lock_guard lock(pa_mutex());
  close_locked(false);
  session_.reset();
}

std::vector<DeviceInfo> default_output_order(const std::vector<DeviceInfo>& outputs) {
  const auto def = std::find_if(outputs.begin(), outputs.end(), [](const DeviceInfo& d) { return d.is_default; });
  if (def == outputs.end()) return {};
  if (def->host_api == "ALSA" && def->name == "default")
    for (const DeviceInfo& d : outputs)
      if (d.host_api == "ALSA" && d.name == "dmix") return {d, *def};
  return {*def};
}

void PortAudioOutput::open_locked() {
  if (!session_) session_ = std::make_unique<Session>();
  const std::vector<DeviceInfo> devices = resolve_locked(config_.device);
  // Each in turn: dmix may be unable to share a card a sound server holds; the last one's
  // error is the one reported.
  for (std::size_t i = 0; i + 1 < devices.size(); ++i) {
    try {
      open_device_locked(devices[i]);
      return;
    } catch (const std::runtime_error& e) {
      if (!fallback_said_) journal::info("{}; opening \"{}\" instead", e.what(), devices.back().name.c_str());
      fallback_said_ = true;  // once: a device's reopening retries come every few seconds
    }
  }
  open_device_locked(devices.back());
}

void PortAudioOutput::open_device_locked(const DeviceInfo& device) {
  if (device.max_output_channels < channels_)
    throw std::runtime_error("audio: \"" + device.name + "\" has " + std::to_string(device.max_output_channels) +
                             " output channel(s); [audio.routing] needs " + std::to_string(channels_));
  PaStreamParameters p{};
  p.device = device.index;
  p.channelCount = channels_;
  p.sampleFormat = options_.format == StreamFormat::int16 ? paInt16 : paFloat32;
  // See UNDERRUNS in the header: never the few-period buffer a device's default or a tiny
  // setting would give, and at least what repeated underruns have grown it to.
  const double asked =
      config_.suggested_latency_ms > 0 ? config_.suggested_latency_ms / 1000.0 : device.default_low_latency_s;
  p.suggestedLatency = std::max({asked, config_.min_latency_ms / 1000.0, grown_latency_s_});
  p.hostApiSpecificStreamInfo = nullptr;
  const unsigned long fpb = config_.frames_per_buffer > 0 ? static_cast<unsigned long>(config_.frames_per_buffer)
                                                          : paFramesPerBufferUnspecified;
  // The capture's input side: the same stream, so that its frames are the played ones'. An
  // input that does not open never silences the kiosk: the stream then only plays (said once).
  PaStream* stream = nullptr;
  capture_in_channels_ = 0;
  input_name_.clear();
  if (options_.capture) {
    try {
      const DeviceInfo in_device = resolve_input_locked(options_.capture->input_device);
      const int needed =
          *std::max_element(options_.capture->input_channels.begin(), options_.capture->input_channels.end()) + 1;
      if (in_device.max_input_channels < needed)
        throw NoInput("this sound card has no input: \"" + in_device.name + "\" records " +
                      std::to_string(in_device.max_input_channels) + " channel(s), channel " + std::to_string(needed) +
                      " was asked for");
      PaStreamParameters in{};
      in.device = in_device.index;
      in.channelCount = needed;
      in.sampleFormat = paFloat32;
      in.suggestedLatency = std::max(in_device.default_low_input_latency_s, p.suggestedLatency);
      if (const PaError e = Pa_OpenStream(&stream, &in, &p, sample_rate_, fpb, paClipOff | paDitherOff,
                                          &Trampoline::callback, this);
          e != paNoError)
        throw std::runtime_error("audio: cannot open \"" + device.name + "\" recording \"" + in_device.name +
                                 "\": " + error_text(e));
      capture_in_channels_ = needed;
      input_name_ = in_device.name;
      capture_problem_said_ = false;
    } catch (const std::exception& e) {
      stream = nullptr;
      if (!capture_problem_said_) journal::error("{}; the stream plays without recording it", e.what());
      capture_problem_said_ = true;  // once: a lost device's reopening retries come every few seconds
    }
  }
  if (!stream)
    if (const PaError e = Pa_OpenStream(&stream, nullptr, &p, sample_rate_, fpb, paClipOff | paDitherOff,
                                        &Trampoline::callback, this);
        e != paNoError)
      throw std::runtime_error("audio: cannot open \"" + device.name + "\" (" + std::to_string(channels_) + " ch, " +
                               std::to_string(sample_rate_) + " Hz, " +
                               (options_.format == StreamFormat::int16 ? "int16" : "float32") + "): " + error_text(e));
  capturing_.store(capture_in_channels_ > 0, std::memory_order_relaxed);
  Pa_SetStreamFinishedCallback(stream, &Trampoline::finished);
  const PaStreamInfo* info = Pa_GetStreamInfo(stream);
  stream_ = stream;
  device_ = device;
  requested_latency_s_ = p.suggestedLatency;
  latency_s_ = info ? info->outputLatency : p.suggestedLatency;
  input_latency_s_ = info && capture_in_channels_ > 0 ? info->inputLatency : 0.0;
  // A measured figure (the operator's latency test, key T) beats the driver's report.
  if (config_.output_latency_ms >= 0) latency_s_ = config_.output_latency_ms * 1e-3;
  stream_rate_ = info ? info->sampleRate : sample_rate_;
}

void PortAudioOutput::start_stream_locked() {
  stream_finished_.store(false, std::memory_order_relaxed);
  // Frame 0 is heard one output latency after the start; frames already rendered (a
  // restart, a reopen) lie before it. See FRAME 0'S TIME in the header.
  const Nanos latency_ns = static_cast<Nanos>(std::llround(latency_s_ * 1e9));
  latency_ns_.store(latency_ns, std::memory_order_relaxed);
  engine_.set_origin(monotonic_now() + latency_ns - frames_to_ns(engine_.position(), sample_rate_));
  if (const PaError e = Pa_StartStream(static_cast<PaStream*>(stream_)); e != paNoError)
    throw std::runtime_error("audio: cannot start \"" + device_.name + "\": " + error_text(e));
}

void PortAudioOutput::close_locked(bool abort) {
  if (!stream_) return;
  auto* stream = static_cast<PaStream*>(stream_);
  if (abort) Pa_AbortStream(stream);  // errors ignored: the device may be gone
  Pa_CloseStream(stream);
  stream_ = nullptr;
}

void PortAudioOutput::start() {
  if (running_) return;
  {
    std::lock_guard lock(pa_mutex());
    if (!stream_) open_locked();
    start_stream_locked();
  }
  running_ = true;
  device_ok_.store(true, std::memory_order_relaxed);
  {
    std::lock_guard lock(wake_mutex_);
    quit_ = false;
  }
  watched_callbacks_ = callbacks_.load(std::memory_order_relaxed);
  last_progress_ = std::chrono::steady_clock::now();
  supervisor_ = std::thread([this] { supervise(); });
}

void PortAudioOutput::stop() {
  if (!running_) return;
  {
    std::lock_guard lock(wake_mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  supervisor_.join();
  {
    std::lock_guard lock(pa_mutex());
    if (stream_) Pa_StopStream(static_cast<PaStream*>(stream_));
  }
  device_ok_.store(false, std::memory_order_relaxed);
  running_ = false;
}

void PortAudioOutput::drop_device() {
  if (!running_) return;
  std::lock_guard lock(pa_mutex());
  if (stream_) Pa_AbortStream(static_cast<PaStream*>(stream_));
}

void PortAudioOutput::grow_buffer() {
  if (running_) grow_requested_.store(true, std::memory_order_relaxed);
}

double PortAudioOutput::requested_latency_s() const {
  std::lock_guard lock(pa_mutex());
  return requested_latency_s_;
}

DeviceInfo PortAudioOutput::device() const {
  std::lock_guard lock(pa_mutex());
  return device_;
}

double PortAudioOutput::output_latency_s() const {
  std::lock_guard lock(pa_mutex());
  return latency_s_;
}

double PortAudioOutput::input_latency_s() const {
  std::lock_guard lock(pa_mutex());
  return input_latency_s_;
}

std::string PortAudioOutput::input_device_name() const {
  std::lock_guard lock(pa_mutex());
  return input_name_;
}

double PortAudioOutput::sample_rate_hz() const {
  std::lock_guard lock(pa_mutex());
  return stream_rate_;
}

OutputCounters PortAudioOutput::counters() const {
  OutputCounters c;
  c.callbacks = callbacks_.load(std::memory_order_relaxed);
  c.frames = frames_.load(std::memory_order_relaxed);
  c.xruns = xruns_.load(std::memory_order_relaxed);
  c.silent_frames = silent_frames_.load(std::memory_order_relaxed);
  c.device_losses = losses_.load(std::memory_order_relaxed);
  c.reopen_attempts = reopen_attempts_.load(std::memory_order_relaxed);
  c.reopens = reopens_.load(std::memory_order_relaxed);
  c.resyncs = resyncs_.load(std::memory_order_relaxed);
  c.buffer_growths = growths_.load(std::memory_order_relaxed);
  return c;
}

// The audio thread. See THE CALLBACK CONTRACT in the header.
int PortAudioOutput::render(const void* input, void* output, unsigned long frames, unsigned long status_flags) {
  if (status_flags & paOutputUnderflow) xruns_.fetch_add(1, std::memory_order_relaxed);
  const Nanos now = monotonic_now();
  if (capture_ && input)
    capture_->write(static_cast<const float*>(input), capture_in_channels_, frames, engine_.position(), now,
                    (status_flags & (paInputOverflow | paInputUnderflow | paOutputUnderflow)) != 0);
  // This buffer is heard no sooner than one output latency from now. If the engine's clock
  // says earlier by more than a buffer, the stream lost time: re-anchor (FRAME 0'S TIME).
  // Never backwards: a callback may run early while the device's buffer fills.
  const Nanos earliest = now + latency_ns_.load(std::memory_order_relaxed);
  const Nanos planned = engine_.origin() + frames_to_ns(engine_.position(), sample_rate_);
  if (earliest - planned > frames_to_ns(static_cast<std::int64_t>(frames), sample_rate_) + 1'000'000) {
    engine_.set_origin(earliest - frames_to_ns(engine_.position(), sample_rate_));
    resyncs_.fetch_add(1, std::memory_order_relaxed);
  }
  if (options_.format == StreamFormat::float32) {
    auto* out = static_cast<float*>(output);
    for (unsigned long done = 0; done < frames;) {
      const auto n = static_cast<int>(std::min<unsigned long>(frames - done, kScratchFrames));
      engine_.process(out + done * static_cast<unsigned long>(channels_), n);
      done += static_cast<unsigned long>(n);
    }
  } else {
    auto* out = static_cast<std::int16_t*>(output);
    for (unsigned long done = 0; done < frames;) {
      const auto n = static_cast<int>(std::min<unsigned long>(frames - done, kScratchFrames));
      engine_.process(scratch_.data(), n);
      const std::size_t samples = static_cast<std::size_t>(n) * static_cast<std::size_t>(channels_);
      std::int16_t* o = out + done * static_cast<unsigned long>(channels_);
      for (std::size_t i = 0; i < samples; ++i)  // same scaling as WavWriter's pcm16
        o[i] = static_cast<std::int16_t>(std::lrint(std::clamp(scratch_[i], -1.0f, 1.0f) * 32767.0f));
      done += static_cast<unsigned long>(n);
    }
  }
  frames_.fetch_add(frames, std::memory_order_relaxed);
  callbacks_.fetch_add(1, std::memory_order_relaxed);
  return paContinue;
}

Check PortAudioOutput::stream_alive_locked() {
  auto* stream = static_cast<PaStream*>(stream_);
  if (!stream) return refused("no stream");
  if (stream_finished_.load(std::memory_order_relaxed)) return refused("the stream ended");
  if (const PaError active = Pa_IsStreamActive(stream); active != 1)
    return refused(active == 0 ? "the stream stopped" : error_text(active));
  const auto now = std::chrono::steady_clock::now();
  const std::uint64_t callbacks = callbacks_.load(std::memory_order_relaxed);
  const auto stall = std::max<std::chrono::steady_clock::duration>(
      options_.stall_timeout, std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(4 * latency_s_)));
  if (callbacks != watched_callbacks_) {
    watched_callbacks_ = callbacks;
    last_progress_ = now;
  } else if (now - last_progress_ > stall) {
    return refused("no audio callback for " +
                   std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(now - last_progress_).count()) +
                   " ms");
  }
  return {};
}

// While the device is gone the engine still consumes impacts and lets voices decay, at
// the wall-clock rate, so that nothing stale bursts out when the device comes back.
void PortAudioOutput::render_silent(std::int64_t frames) {
  while (frames > 0) {
    const auto n = static_cast<int>(std::min<std::int64_t>(frames, kScratchFrames));
    engine_.process(scratch_.data(), n);
    silent_frames_.fetch_add(static_cast<std::uint64_t>(n), std::memory_order_relaxed);
    frames -= n;
  }
}

bool PortAudioOutput::grow_locked() {
  const double ceiling = config_.max_latency_ms / 1000.0;
  if (requested_latency_s_ >= ceiling) return false;
  grown_latency_s_ = std::min(2 * requested_latency_s_, ceiling);
  close_locked(true);  // joins the audio thread: the engine is ours until the new stream starts
  open_locked();
  start_stream_locked();
  return true;
}

void PortAudioOutput::supervise() {
  using Clock = std::chrono::steady_clock;
  const auto xrun_interval = std::chrono::duration_cast<Clock::duration>(options_.xrun_log_interval);
  auto last_xrun_log = Clock::now() - xrun_interval;
  std::uint64_t xruns_logged = xruns_.load(std::memory_order_relaxed);
  bool lost = false;
  bool retry_failure_logged = false;
  std::uint64_t attempts = 0;  // in this outage
  std::chrono::milliseconds backoff = options_.first_retry;
  Clock::time_point retry_at{}, silent_since{};
  std::int64_t silent_base = 0;
  // UNDERRUNS: a window opens at the first underrun and counts those within it.
  const auto underrun_window = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double, std::milli>(config_.underrun_window_ms));
  const auto grow_after = static_cast<std::uint64_t>(config_.grow_after_underruns);
  std::uint64_t xruns_seen = xruns_.load(std::memory_order_relaxed), window_base = 0;
  bool window_open = false, ceiling_logged = false;
  bool fixed_buffer = false;  // a reopen with a larger buffer asked came back no larger
  Clock::time_point window_start{};

  // The stream is closed (the audio thread joined): run silent and retry with backoff.
  auto lose = [&](const std::string& name, const std::string& why, Clock::time_point now) {
    lost = true;
    retry_failure_logged = false;
    attempts = 0;
    device_ok_.store(false, std::memory_order_relaxed);
    losses_.fetch_add(1, std::memory_order_relaxed);
    journal::warning("audio: output \"{}\" lost ({}); running silent, retrying to open \"{}\"", name.c_str(),
                     why.c_str(), config_.device.empty() ? "the default device" : config_.device.c_str());
    backoff = options_.first_retry;
    retry_at = now + backoff;
    silent_since = now;
    silent_base = engine_.position();
  };

  for (;;) {
    {
      std::unique_lock lock(wake_mutex_);
      if (wake_.wait_for(lock, options_.poll_interval, [this] { return quit_; })) break;
    }
    const auto now = Clock::now();

    if (!lost) {
      Check alive;
      std::string name;
      {
        std::lock_guard lock(pa_mutex());
        alive = stream_alive_locked();
        name = device_.name;
        if (!alive) close_locked(true);  // joins the audio thread: the engine is ours now
      }
      if (!alive) lose(name, alive.error(), now);
    }

    if (!lost) {
      const std::uint64_t xruns = xruns_.load(std::memory_order_relaxed);
      if (window_open && now - window_start > underrun_window) window_open = false;
      if (!window_open && xruns > xruns_seen) {
        window_open = true;
        window_start = now;
        window_base = xruns_seen;
      }
      xruns_seen = xruns;
      const bool asked = grow_requested_.exchange(false, std::memory_order_relaxed) && !fixed_buffer;
      const bool repeated = grow_after > 0 && !fixed_buffer && window_open && xruns - window_base >= grow_after;
      if (asked || repeated) {
        window_open = false;
        std::string name, failure;
        double before = 0, after = 0, asked_s = 0;
        bool grown = false;
        {
          std::lock_guard lock(pa_mutex());
          name = device_.name;
          before = latency_s_;
          try {
            grown = grow_locked();
          } catch (const std::exception& e) {
            failure = e.what();
          }
          after = latency_s_;
          asked_s = requested_latency_s_;
          watched_callbacks_ = callbacks_.load(std::memory_order_relaxed);
          last_progress_ = Clock::now();
        }
        if (!failure.empty()) {
          lose(name, "reopening it with a larger buffer failed: " + failure, now);
        } else if (grown && after <= before * 1.001) {
          fixed_buffer = true;
          journal::warning(
              "audio: \"{}\" came back with the same output latency, {:.1f} ms, when reopened with a larger "
              "buffer asked ({:.0f} ms): its server or driver sets the buffer (JACK: its period), so underruns "
              "there are no longer answered by reopening it",
              name.c_str(), after * 1e3, asked_s * 1e3);
        } else if (grown && !repeated) {
          growths_.fetch_add(1, std::memory_order_relaxed);
          journal::info("audio: reopened \"{}\" with a larger buffer as asked, output latency {:.1f} ms "
                        "(was {:.1f} ms)",
                        name.c_str(), after * 1e3, before * 1e3);
        } else if (grown) {
          growths_.fetch_add(1, std::memory_order_relaxed);
          journal::warning(
              "audio: {} output underrun(s) within {:g} ms on \"{}\": reopened it with a larger buffer, output "
              "latency {:.1f} ms (was {:.1f} ms; at most [audio].max_latency_ms = {:g})",
              xruns - window_base, config_.underrun_window_ms, name.c_str(), after * 1e3, before * 1e3,
              config_.max_latency_ms);
        } else if (!ceiling_logged) {
          ceiling_logged = true;
          journal::warning(
              "audio: underruns go on with the largest buffer allowed ([audio].max_latency_ms = {:g}, output latency "
              "{:.1f} ms); the machine is too busy for its sound",
              config_.max_latency_ms, after * 1e3);
        }
      }
    }

    if (lost) {
      const double elapsed = std::chrono::duration<double>(now - silent_since).count();
      const auto due = static_cast<std::int64_t>(elapsed * sample_rate_) - (engine_.position() - silent_base);
      if (due > sample_rate_) {  // far behind (a stalled machine): skip, do not catch up
        silent_since = now;
        silent_base = engine_.position();
      } else {
        render_silent(due);
      }
      if (now >= retry_at) {
        reopen_attempts_.fetch_add(1, std::memory_order_relaxed);
        ++attempts;
        std::string name;
        double latency = 0;
        try {
          std::lock_guard lock(pa_mutex());
          close_locked(true);
          session_.reset();  // re-initialise so that PortAudio enumerates a replugged card
          session_ = std::make_unique<Session>();
          open_locked();
          start_stream_locked();
          name = device_.name;
          latency = latency_s_;
          watched_callbacks_ = callbacks_.load(std::memory_order_relaxed);
          last_progress_ = Clock::now();
        } catch (const std::exception& e) {
          if (!retry_failure_logged)
            journal::warning("audio: reopening failed ({}); retrying with backoff up to {} ms", e.what(),
                             static_cast<long long>(options_.max_retry.count()));
          retry_failure_logged = true;
          backoff = std::min(backoff * 2, options_.max_retry);
          retry_at = Clock::now() + backoff;
          continue;
        }
        lost = false;
        device_ok_.store(true, std::memory_order_relaxed);
        reopens_.fetch_add(1, std::memory_order_relaxed);
        journal::info("audio: output \"{}\" reopened after {} attempt(s); output latency {:.1f} ms", name.c_str(),
                      attempts, latency * 1e3);
      }
    }

    const std::uint64_t xruns = xruns_.load(std::memory_order_relaxed);
    if (xruns > xruns_logged && now - last_xrun_log >= xrun_interval) {
      journal::warning(
          "audio: {} output underrun(s) since the last report ({} in all); if they persist, raise [audio] "
          "min_latency_ms (grow_after_underruns grows the buffer by itself)",
          xruns - xruns_logged, xruns);
      xruns_logged = xruns;
      last_xrun_log = now;
    }
  }
}

}  // namespace mallet::audio
