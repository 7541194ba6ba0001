#pragma once
// A device's native sample rate as the operator page shows it: how many samples were stamped
// in the last second. Counted on the samples' own timestamps, not on when the program got
// round to them, so a reading thread that was late does not make the mouse look slow, and a
// test drives it with recorded times. Fixed memory: a ring of the last second's stamps.
#include <cstddef>
#include <vector>

#include "core/time.hpp"

namespace mallet::input::evdev {

class RateMeter {
 public:
  //! Up to `capacity` stamps a second are counted exactly (8192: the fastest gaming mice
  //! report at 8 kHz); beyond that the rate reads as `capacity`.
  explicit RateMeter(std::size_t capacity = 8192) : stamps_(capacity > 0 ? capacity : 1) {}

  //! One sample stamped at `t_ns` (stamps arrive in non-decreasing order).
  void add(Nanos t_ns) {
    if (size_ == stamps_.size()) {  // full: the oldest goes
      first_ = (first_ + 1) % stamps_.size();
      --size_;
    }
    stamps_[(first_ + size_) % stamps_.size()] = t_ns;
    ++size_;
  }

  //! Samples stamped in (now_ns − 1 s, now_ns], i.e. samples per second.
  double rate_hz(Nanos now_ns) {
    while (size_ > 0 && stamps_[first_] <= now_ns - kNanosPerSecond) {
      first_ = (first_ + 1) % stamps_.size();
      --size_;
    }
    return static_cast<double>(size_);
  }

  void clear() { first_ = size_ = 0; }

 private:
  std::vector<Nanos> stamps_;
  std::size_t first_ = 0;
  std::size_t size_ = 0;
};

}  // namespace mallet::input::evdev
