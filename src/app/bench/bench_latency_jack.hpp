#pragma once
// The audio side of `mallet bench latency`: a JACK server of the bench's own and a
// recorder client that listens to the kiosk's output ports.
//
// Why JACK: the sample clock must be wall time. JACK's dummy driver runs its cycles on a
// real-time timer (-r 48000 -p 128: a cycle every 2.67 ms), and each cycle's first frame
// has a time (jack_frames_to_time of jack_last_frame_time) on JACK's clock, which is
// CLOCK_MONOTONIC_RAW in jackd2 and is converted to the kiosk's CLOCK_MONOTONIC. ALSA's
// file plugin, the other sound-card-free path on these machines, is not paced: PortAudio
// writes into it as fast as it can, so a sample's index there says nothing about when it
// would have been heard.
//
// The recorder's process callback stamps each cycle's buffers with that cycle's time and
// copies them into a preallocated single-producer / single-consumer ring (no lock, no
// allocation, no call that can block in the callback); the main thread drains it into an
// AudioTrack and looks for strikes there (bench_latency_onset).
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/bench/bench_latency_child.hpp"
#include "app/bench/bench_latency_onset.hpp"
#include "core/time.hpp"

typedef struct _jack_client jack_client_t;
typedef struct _jack_port jack_port_t;

namespace mallet::app::latency {

//! The audio ports of every client but the system and `self`, in one direction (JackPortIsOutput
//! or JackPortIsInput), by client name, each client's in channel order (out_0 … out_9, out_10:
//! by length, then name): where the kiosk's PortAudio stream is found on a bench's server.
std::map<std::string, std::vector<std::string>> ports_by_client(jack_client_t* self, unsigned long flags);

//! JACK's clock (jack_get_time) less the monotonic clock, in ns: the tightest of 50 readings.
//! jackd2 keeps its own time base (CLOCK_MONOTONIC_RAW on Linux).
Nanos jack_clock_offset_ns();

//! jackd --no-realtime -n NAME -d dummy -r RATE -p PERIOD [-C CAPTURE], up and accepting clients.
class JackServer {
 public:
  //! Starts it and waits (bounded) until a client can connect; throws when it cannot.
  //! `capture`: the system's capture channels (0: the dummy driver's own 2).
  JackServer(const std::string& name, int rate, int period, int capture = 0);
  const std::string& name() const { return name_; }
  Child& server() { return *server_; }

 private:
  std::string name_;
  std::unique_ptr<Child> server_;
};

//! What the recorder heard while it recorded: each channel's samples, and per JACK cycle
//! the index of its first sample and the monotonic time a device would play that sample.
struct AudioTrack {
  struct Block {
    std::size_t index = 0;  //!< of its first sample in `channels[c]`
    Nanos t = 0;
  };
  int rate = 0;
  std::vector<std::vector<float>> channels;
  std::vector<Block> blocks;

  //! The time of sample i; of the sample at (or just after) time t.
  Nanos time_of(std::size_t i) const;
  std::size_t index_at(Nanos t) const;
  //! The cycles that did not follow their predecessor by one period (±0.2 ms): an xrun,
  //! where the kiosk's stream may have skipped. Each as the samples of the cycle before,
  //! itself and the one after.
  std::vector<Gap> irregular(int period) const;
};

//! The recorder: a JACK client with one input port per channel.
class JackRecorder {
 public:
  JackRecorder(const std::string& server, int channels);
  ~JackRecorder();
  JackRecorder(const JackRecorder&) = delete;
  JackRecorder& operator=(const JackRecorder&) = delete;

  //! Connects the output ports of the one client that is neither the system nor us (the
  //! kiosk's PortAudio), channel i to input i, once `channels` of them exist. Waits up to
  //! `timeout`; returns the ports connected (empty on timeout).
  std::vector<std::string> connect_source(std::chrono::milliseconds timeout);
  //! Starts copying what the ports hear into the ring (empty), into a fresh `track`.
  void start_recording(AudioTrack& track);
  //! Moves what the ring holds into `track` (the main thread, often enough: the ring holds
  //! 10 s); the cycle times converted to the monotonic clock and a device's playback time.
  //! First follows the source if it reopened its stream (follow_source).
  void drain(AudioTrack& track);
  //! When the kiosk reopens its stream (a larger buffer after underruns: a new PortAudio
  //! client, whose ports nobody has connected), connects its new ports, as a sound card stays
  //! wired through a reopen; the recording goes on. True when it did. Without it the
  //! recorder heard silence from the reopen on.
  bool follow_source();
  //! How often follow_source connected a reopened stream.
  std::uint64_t reopens_followed() const { return reopens_followed_; }
  void stop_recording() { recording_.store(false, std::memory_order_release); }
  //! Drops the track's samples (and cycle stamps) before sample `index`, so that a recording
  //! of hours keeps only what is still to be looked at; indices shift down by `index`.
  void forget_before(AudioTrack& track, std::size_t index);
  //! Measures clock_offset_ns() again (the main thread; the two clocks drift apart by tens
  //! of µs a minute while NTP slews CLOCK_MONOTONIC, which a run of hours must follow).
  void measure_clock();
  //! How much later than its cycle's start a sample written in that cycle is played by a
  //! device (the system playback ports' latency): added to every onset.
  Nanos playback_latency_ns() const { return playback_latency_ns_; }
  //! The JACK clock minus the monotonic clock, measured when the source is connected.
  //! jackd2 keeps its own time base (CLOCK_MONOTONIC_RAW on Linux: ≈ −250 ms here), so
  //! every cycle time is converted.
  Nanos clock_offset_ns() const { return clock_offset_ns_; }
  int rate() const { return rate_; }
  int period() const { return period_; }
  std::uint64_t xruns() const { return xruns_.load(); }
  std::uint64_t cycles() const { return cycles_.load(); }
  std::uint64_t dropped() const { return dropped_.load(); }  //!< cycles the ring had no room for

 private:
  static int process(std::uint32_t frames, void* self);
  static int xrun(void* self);

  jack_client_t* client_ = nullptr;
  std::vector<jack_port_t*> ports_;
  int rate_ = 0, period_ = 0;
  Nanos playback_latency_ns_ = 0;
  Nanos clock_offset_ns_ = 0;
  std::uint64_t reopens_followed_ = 0;  //!< the main thread's
  std::atomic<std::uint64_t> xruns_{0}, cycles_{0}, dropped_{0};
  std::atomic<bool> recording_{false};
  // The SPSC rings: the callback writes samples (per channel) and cycle stamps and then
  // publishes the counts; the main thread reads up to them and publishes what it took.
  static constexpr std::uint64_t kFrames = 1u << 19;  // ≈10.9 s at 48 kHz
  static constexpr std::uint64_t kCycles = 1u << 13;
  struct Stamp {
    std::uint64_t frame = 0;  //!< the ring count of its first sample
    Nanos jack_ns = 0;        //!< the cycle's time on the JACK clock
  };
  std::vector<std::unique_ptr<float[]>> samples_;
  std::unique_ptr<Stamp[]> stamps_;
  std::atomic<std::uint64_t> frames_written_{0}, frames_read_{0}, stamps_written_{0}, stamps_read_{0};
  std::uint64_t track_origin_ = 0;  //!< the ring count of the track's first sample (main thread)
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);
  static_assert(std::atomic<bool>::is_always_lock_free);
};

}  // namespace mallet::app::latency
