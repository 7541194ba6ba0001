#pragma once
// A recording made inside the kiosk's own output stream: input channels of the same
// full-duplex stream that plays the kiosk's sound, kept for a fixed length once armed, each
// callback's block stamped with the engine's frame position and the monotonic time the
// callback ran. `mallet calibrate latency --photodiode` records a photodiode on the screen's
// corner this way while the operator page's latency test (T) flashes its square
// (audio/photodiode_timing.hpp reads the recording).
//
// Preallocated when made: the callback copies and counts (no allocation, no lock). The
// main thread arms it, waits until it is complete, then reads it; the callback writes nothing
// once it is complete, so reading then races with nothing.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/time.hpp"

namespace mallet::audio {

//! What the kiosk's stream records besides playing: input channels of an input device.
struct CaptureSpec {
  std::string input_device;         //!< as `--input`: empty = the default input
  std::vector<int> input_channels;  //!< 0-based, in the order they are kept
  double seconds = 14;              //!< the recording's length once armed
};

//! One callback's block: where it starts in the recording and on the engine's frames, and
//! when the callback ran.
struct CaptureBlock {
  std::size_t index = 0;       //!< its first frame in the recording
  std::int64_t position = 0;   //!< the engine's frame position of its first frame
  Nanos callback_ns = 0;       //!< monotonic, as the callback began
  bool xrun = false;           //!< the stream flagged it as over- or underflowing
};

struct CaptureRecording {
  int sample_rate_hz = 0;
  std::vector<std::vector<float>> channels;  //!< one per CaptureSpec::input_channels
  std::vector<CaptureBlock> blocks;
  unsigned long xruns = 0;  //!< blocks flagged as over- or underflowing
  bool continuous = true;   //!< every block followed the one before on the engine's frames
};

class StreamCapture {
 public:
  StreamCapture(int sample_rate_hz, std::vector<int> input_channels, double seconds);

  // The audio thread's. `in` holds `frames` interleaved frames of `in_channels`; `position`
  // is the engine's frame position of the first.
  void write(const float* in, int in_channels, unsigned long frames, std::int64_t position, Nanos now, bool xrun);

  // The main thread's.
  //! Starts a recording from the next callback on (not while one is under way).
  void arm();
  bool armed() const { return armed_.load(std::memory_order_acquire); }
  bool complete() const { return written_.load(std::memory_order_acquire) >= frames_; }
  //! The recording; only once complete().
  CaptureRecording recording() const;
  const std::vector<int>& input_channels() const { return picks_; }

 private:
  int rate_;
  std::vector<int> picks_;
  std::size_t frames_;
  std::vector<float> samples_;       //!< frames_ × picks, interleaved
  std::vector<CaptureBlock> blocks_; //!< preallocated: frames_ / 16 + 1
  std::atomic<bool> armed_{false};
  std::atomic<std::size_t> written_{0};
  std::size_t block_count_ = 0;      //!< the audio thread's until complete
  std::atomic<unsigned long> xruns_{0};
  bool continuous_ = true;           //!< the audio thread's until complete
};

}  // namespace mallet::audio
