#pragma once
// The kiosk's real audio output: one PortAudio stream (ALSA host API on Debian) whose
// callback is AudioEngine::process(). Channel 0/1 carry what [audio.routing] says
// (default 0 = the speaker's note, 1 = the voice coil's Eq. 1).
//
// THE CALLBACK CONTRACT. The PortAudio callback (a private static function) runs on
// PortAudio's audio thread and only: calls engine.process() into PortAudio's buffer
// (or, for int16 streams, into a buffer preallocated by the constructor, then converts),
// counts callbacks and frames, and counts output underruns (paOutputUnderflow) in
// relaxed atomics. It never locks, allocates, logs, throws or waits; nothing it
// touches is created or destroyed while the stream runs. Everything else — logging,
// reopening, every other PortAudio call — happens on the caller's thread or on the
// supervisor thread, under one process-wide mutex (PortAudio is not thread-safe).
//
// FRAME 0'S TIME. start() sets engine.set_origin(now + outputLatency − position/fs)
// just before Pa_StartStream: now on std::chrono::steady_clock, outputLatency as
// PortAudio reports it for the opened stream (Pa_GetStreamInfo), position the frames
// the engine has already rendered (0 on the first start; continued across reopens). We
// do not use the first callback's PaStreamCallbackTimeInfo: on Linux PortAudio 19.6
// stamps it with CLOCK_REALTIME (PaUtil_GetTime), not the monotonic clock of Impact::t_ns,
// and the engine's origin may only change while no callback runs. The error is the
// start-up time between Pa_StartStream and the first callback plus whatever PortAudio's
// latency figure leaves out; it is fixed at start and does not grow while the stream runs
// (apart from the drift between the sound card's clock and the system's). A stream that
// falls behind (an xrun: the device played silence, or a server such as JACK skipped the
// time it was late) would leave every later strike late by that much: the callback then
// moves the origin forward to when its buffer can really be heard (counted in
// OutputCounters::resyncs). It is the audio thread's own change, between two process()
// calls, so the engine never sees it mid-block.
//
// DEVICE LOSS. A supervisor thread (not the audio thread) polls every
// Options::poll_interval: if the stream is no longer active (Pa_IsStreamActive false,
// e.g. a USB card unplugged → paUnanticipatedHostError), PortAudio called the
// stream-finished callback (an atomic flag set on the audio thread), or no callback
// arrived for Options::stall_timeout while the stream claims to run, it logs one
// warning (and, if the first reopen fails, its reason once), aborts and closes the stream, and from then on renders the engine silently
// into a scratch buffer at the wall-clock rate (so posted impacts are consumed and the
// timeline keeps moving instead of bursting out on recovery) while it retries to open
// the configured device — looked up again by name, after re-initialising PortAudio so
// that a replugged card is seen — with exponential backoff (first_retry doubling up to
// max_retry). Recovery logs one info line with the new latency. The application is never
// restarted and start() / the destructor remain valid throughout. (Pa_Initialize is
// reference-counted: a rescan happens only if nothing else in the process holds
// PortAudio open at that moment.)
//
// UNDERRUNS. The callback counts paOutputUnderflow; the supervisor logs the count at most
// once per Options::xrun_log_interval (10 s by default). An underrun is not only a click:
// through ALSA's `default` PCM on a card with dmix (Debian 12: plug → softvol → dmix, e.g.
// HDA-Intel) it can abort the process, and nothing in-process can catch that. alsa-lib
// 1.2.8's snd_pcm_dmix_mmap_commit moves dmix's application pointer forward *before*
// snd_pcm_dmix_sync_ptr finds the underrun and returns -EPIPE; the softvol/plug converter
// above it (snd_pcm_plugin_mmap_commit) then does not move its own, and the next
// snd_pcm_status() hits snd_pcm_plugin_status's `assert(status->appl_ptr ==
// *pcm->appl.ptr)` (pcm_plugin.c; still there in 1.2.11 and later). PortAudio 19.6 always
// calls snd_pcm_status() next: for the callback's time info, or in its xrun handler before
// snd_pcm_prepare. So every underrun that dmix notices inside a commit (rather than in
// avail_update or poll) kills the kiosk: a race that heavy underruns win now and then
// (twice in ~272 underruns in 10 s in a QEMU guest; again in the package's VM test, after
// 1690). So an empty [audio] device opens ALSA's "dmix" PCM itself where PortAudio's default
// is ALSA's "default" (default_output_order): the same mixer on the same card, with no
// snd_pcm_plugin layer above it (PortAudio converts the samples to dmix's format itself),
// hence no such assert on the path; where dmix cannot open (a sound server holds the card)
// the default is opened as before. A device named in [audio] device is opened as named.
// Mallet also makes underruns rare and stops them from going on: PortAudio's suggested latency (≈ the ALSA buffer less one
// period) is never below [audio] min_latency_ms, and when [audio] grow_after_underruns
// underruns come within underrun_window_ms (counted from the first), the supervisor
// reopens the same device with twice the latency, up to max_latency_ms, logs one warning
// line and counts it (OutputCounters::buffer_growths), while the engine's timeline goes on
// (FRAME 0'S TIME). A grown buffer stays for this object's life (device reopens included).
// A device that comes back with no longer an output latency than before keeps its buffer
// whatever is asked (a JACK server sets its own period; a driver may fix the buffer): one
// warning says so, the reopen is not counted as a growth, and underruns there are no longer
// answered by reopening it (each reopen is a gap in the sound, and, on JACK, a new client
// whose ports must be connected again).
//
// LOGGING. Plain stderr lines with journald priority prefixes: "<4>" warning, "<6>" info,
// written only by the supervisor and the caller's threads.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "audio/engine.hpp"
#include "audio/stream_capture.hpp"
#include "core/app_config.hpp"
#include "core/result.hpp"

namespace mallet::audio {

//! One PortAudio output device, as `mallet audio devices` lists it.
struct DeviceInfo {
  int index = -1;                    //!< PortAudio device index (valid until PortAudio is re-initialised)
  std::string name;
  std::string host_api;              //!< "ALSA", "JACK Audio Connection Kit", ...
  int max_output_channels = 0;
  int max_input_channels = 0;
  double default_sample_rate_hz = 0;
  double default_low_latency_s = 0;  //!< PortAudio's defaultLowOutputLatency
  bool is_default = false;           //!< the default output device of the default host API
  bool is_default_input = false;     //!< the default input device of the default host API
  double default_low_input_latency_s = 0;  //!< PortAudio's defaultLowInputLatency
};

//! Every output device PortAudio sees (initialises and terminates PortAudio itself).
//! Throws std::runtime_error if PortAudio cannot be initialised.
std::vector<DeviceInfo> list_output_devices();

//! The devices an empty [audio] device tries, in order, among `outputs` (one marked
//! is_default): ALSA's "dmix" PCM first where the default is ALSA's "default" PCM (see
//! UNDERRUNS), then the default. Empty if none is the default.
std::vector<DeviceInfo> default_output_order(const std::vector<DeviceInfo>& outputs);

//! The sample type of the device stream. The engine always renders float; int16 is
//! converted in the callback, for devices or ALSA plugins that must be fed 16-bit
//! (the ALSA file plugin labels float data as integer PCM in its WAV header).
enum class StreamFormat { float32, int16 };

struct OutputCounters {
  std::uint64_t callbacks = 0;       //!< audio callbacks run
  std::uint64_t frames = 0;          //!< frames delivered to the device by callbacks
  std::uint64_t xruns = 0;           //!< callbacks flagged paOutputUnderflow
  std::uint64_t silent_frames = 0;   //!< frames rendered to nowhere while the device was gone
  std::uint64_t device_losses = 0;   //!< times the stream was found stopped or stalled
  std::uint64_t reopen_attempts = 0; //!< tries to open the device again
  std::uint64_t reopens = 0;         //!< successful reopens
  std::uint64_t resyncs = 0;         //!< the stream fell behind its clock and was re-anchored
  std::uint64_t buffer_growths = 0;  //!< reopened with a larger buffer after repeated underruns
};

class PortAudioOutput {
 public:
  struct Options {
    StreamFormat format = StreamFormat::float32;
    std::chrono::milliseconds poll_interval{20};
    std::chrono::milliseconds stall_timeout{2000};   //!< no callback this long = device lost
    std::chrono::milliseconds first_retry{250};
    std::chrono::milliseconds max_retry{5000};
    std::chrono::milliseconds xrun_log_interval{10000};
    //! Also record these input channels in the same (full-duplex) stream, for capture():
    //! `mallet calibrate latency --photodiode`. The input device must be of the output's
    //! host API; one that does not open (or records fewer channels) leaves the stream playing
    //! only, said once in the journal.
    std::optional<CaptureSpec> capture;
  };

  //! Initialises PortAudio and opens (does not start) an output stream on
  //! config.device: empty = the default output device (default_output_order), all digits = a device index,
  //! otherwise a case-insensitive part of the device name (the first match). Channels,
  //! sample rate and routing come from the engine's settings (which must agree with
  //! config); frames_per_buffer (0 = PortAudio chooses), suggested_latency_ms (0 = the
  //! device's default low latency, never below min_latency_ms) and the underrun policy
  //! (grow_after_underruns, underrun_window_ms, max_latency_ms; see UNDERRUNS) from config.
  //! Throws std::runtime_error with one clear line (no such device: the list of those that
  //! exist) on failure. `engine` must outlive this object.
  PortAudioOutput(AudioEngine& engine, const AudioConfig& config, Options options);
  PortAudioOutput(AudioEngine& engine, const AudioConfig& config) : PortAudioOutput(engine, config, Options{}) {}
  //! Stops the supervisor and the stream, closes it, terminates PortAudio.
  ~PortAudioOutput();
  PortAudioOutput(const PortAudioOutput&) = delete;
  PortAudioOutput& operator=(const PortAudioOutput&) = delete;

  //! Sets the engine's origin (see FRAME 0'S TIME), starts the stream and the
  //! supervisor. Throws std::runtime_error if the stream cannot start.
  void start();
  //! Stops the supervisor, then the stream (letting queued buffers play). Idempotent.
  //! start() may be called again afterwards.
  void stop();

  //! Aborts the device stream as a vanished device would (tests; an operator's
  //! "reconnect audio" action). The supervisor then logs the loss, runs silent and
  //! reopens the device with backoff. No effect unless started.
  void drop_device();

  //! Reopens the device with twice the latency (up to [audio] max_latency_ms), as repeated
  //! underruns do (tests; an operator's action). The supervisor does it at its next poll.
  //! No effect unless started.
  void grow_buffer();

  //! The device now in use (as opened, or as last reopened).
  DeviceInfo device() const;
  //! The stream's output latency in seconds, as PortAudio reports it (Pa_GetStreamInfo).
  double output_latency_s() const;
  //! The latency the stream was asked for (PortAudio's suggestedLatency), in seconds: the
  //! configured or default one, at least min_latency_ms, doubled by each buffer growth.
  double requested_latency_s() const;
  //! The sample rate the stream runs at (Pa_GetStreamInfo).
  double sample_rate_hz() const;
  //! True while a device stream is open and running (false while silent after a loss).
  bool device_ok() const { return device_ok_.load(std::memory_order_relaxed); }

  OutputCounters counters() const;

  //! The recording the stream keeps when Options::capture asked for one and its input opened
  //! (else null; why is in the journal): armed and read by the caller's thread, written by the
  //! callback. It lives as long as this.
  StreamCapture* capture() { return capturing_.load(std::memory_order_relaxed) ? capture_.get() : nullptr; }
  //! The stream's input latency as PortAudio reports it (0 without a capture), and its input
  //! device's name.
  double input_latency_s() const;
  std::string input_device_name() const;

 private:
  class Session;      // RAII Pa_Initialize / Pa_Terminate
  struct Trampoline;  // the PortAudio callbacks (they need PortAudio's types)

  int render(const void* input, void* output, unsigned long frames, unsigned long status_flags);  // audio thread

  // All below with pa_mutex held.
  void open_locked();  // the configured device, or the first of default_output_order that opens
  void open_device_locked(const DeviceInfo& device);
  bool fallback_said_ = false;  // open_locked's line when the first choice did not open
  void start_stream_locked();
  void close_locked(bool abort);

  void supervise();
  //! Reopens the stream with twice the requested latency (at most max_latency_ms). False,
  //! with nothing done, when the buffer is at its ceiling already; throws (the stream then
  //! closed) when the device cannot be opened again. Supervisor thread.
  bool grow_locked();
  void render_silent(std::int64_t frames);
  //! Passes while the stream plays; else fails with why it was lost.
  Check stream_alive_locked();

  AudioEngine& engine_;
  AudioConfig config_;
  Options options_;
  int channels_;
  int sample_rate_;

  std::unique_ptr<Session> session_;
  void* stream_ = nullptr;  // PaStream*
  DeviceInfo device_;
  double latency_s_ = 0;
  std::unique_ptr<StreamCapture> capture_;  //!< Options::capture's, preallocated
  int capture_in_channels_ = 0;             //!< the input side's channel count (0: it did not open)
  std::atomic<bool> capturing_{false};      //!< the open stream records
  bool capture_problem_said_ = false;
  double input_latency_s_ = 0;
  std::string input_name_;
  double requested_latency_s_ = 0;  //!< suggestedLatency of the open stream
  double grown_latency_s_ = 0;      //!< the floor set by buffer growths (0 = none yet)
  std::atomic<Nanos> latency_ns_{0};  //!< latency_s_ for the audio thread
  std::atomic<std::uint64_t> resyncs_{0};
  double stream_rate_ = 0;
  std::vector<float> scratch_;  // int16 conversion and silent rendering; sized once

  std::thread supervisor_;
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  bool quit_ = false;     // under wake_mutex_
  std::uint64_t watched_callbacks_ = 0;                // supervisor: the stall watchdog
  std::chrono::steady_clock::time_point last_progress_;
  bool running_ = false;  // start() called and not stopped; caller's thread only

  std::atomic<bool> device_ok_{false};
  std::atomic<bool> stream_finished_{false};
  std::atomic<bool> grow_requested_{false};
  std::atomic<std::uint64_t> callbacks_{0}, frames_{0}, xruns_{0}, silent_frames_{0}, losses_{0},
      reopen_attempts_{0}, reopens_{0}, growths_{0};
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);
  static_assert(std::atomic<bool>::is_always_lock_free);
};

}  // namespace mallet::audio
