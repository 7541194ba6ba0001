#pragma once
// The bench's photodiode: what a photodiode on the screen's top-left corner, wired to a sound
// card's input, would give the kiosk, made from the bench's own X server and JACK server.
//
// A thread polls the corner's pixels (XGetImage, ≈1 ms apart) and notes each moment it turns
// white or dark: the middle of [the previous grab's request, this grab's reply], as the
// latency bench times its pictures. A JACK client puts that light on an output port, wired to
// the kiosk's capture port, as a sound card's input would deliver it: a panel that lights
// `panel_lag` after the X server shows the frame, and an input that delivers a sample
// `input_latency` after it reached the converter (the figure PortAudio reports for the
// kiosk's stream, which the kiosk's reading of its recording assumes). So the display latency
// the kiosk should find for a square is exactly (turned white − the frame's present) + panel_lag.
//
// The process callback only reads a lock-free ring of the watcher's changes and writes
// samples (no allocation, no lock).
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/bench/bench_latency_x11.hpp"
#include "audio/spsc_ring.hpp"
#include "core/time.hpp"

typedef struct _jack_client jack_client_t;
typedef struct _jack_port jack_port_t;

namespace mallet::app::latency {

class JackPhotodiode {
 public:
  //! Watches `corner` of the X server `display`; a client of the JACK server `server`.
  JackPhotodiode(const std::string& server, const std::string& display, PixelBox corner, Nanos panel_lag);
  ~JackPhotodiode();
  JackPhotodiode(const JackPhotodiode&) = delete;
  JackPhotodiode& operator=(const JackPhotodiode&) = delete;

  //! The input's latency the light is delivered with (set once the kiosk's stream says it).
  void set_input_latency(Nanos latency) { input_latency_.store(latency, std::memory_order_relaxed); }
  //! Wires the light into capture port `channel` (0-based) of the one client (neither the
  //! system nor a bench client) that has at least that many: the kiosk's stream. True once wired.
  bool wire(int channel);
  //! The moments the corner turned white, so far (the main thread).
  std::vector<Nanos> turned_white();
  //! Changes the callback applied later than their time (the JACK cycle had begun): each
  //! puts that change late by up to a period.
  std::uint64_t late() const { return late_.load(std::memory_order_relaxed); }
  std::uint64_t polls() const { return polls_.load(std::memory_order_relaxed); }

 private:
  struct Change {
    Nanos t = 0;  //!< when the light changed on the panel (monotonic)
    float level = 0;
  };
  static int process(std::uint32_t frames, void* self);
  void watch(std::string display, PixelBox corner);

  jack_client_t* client_ = nullptr;
  jack_port_t* port_ = nullptr;
  int rate_ = 48000;
  Nanos panel_lag_ = 0;
  Nanos clock_offset_ns_ = 0;  //!< JACK's clock − the monotonic clock
  std::atomic<Nanos> input_latency_{0};
  audio::SpscRing<Change, 1024> changes_;
  // The process thread's: the change waiting for its sample, and the level until then.
  bool has_next_ = false;
  Change next_{};
  float level_ = 0;
  std::atomic<std::uint64_t> late_{0}, polls_{0};
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<Nanos> white_;
  std::string error_;
  std::thread watcher_;
};

}  // namespace mallet::app::latency
