#pragma once
// The time a pointer source reads and the way it waits, behind a small interface so that
// reconnection, back-off and time-outs are tested with a scripted clock instead of sleeps.
#include <chrono>
#include <thread>

#include "core/time.hpp"

namespace mallet::input {

class Clock {
 public:
  virtual ~Clock() = default;
  //! Now on the program's one monotonic clock, int64 nanoseconds.
  virtual Nanos now() = 0;
  //! Waits about `duration_ns` (≥ 0). A fake advances its time instead.
  virtual void sleep_for(Nanos duration_ns) = 0;
};

class SteadyClock final : public Clock {
 public:
  Nanos now() override { return monotonic_now(); }  // core/time.hpp: the clock every timestamp uses
  void sleep_for(Nanos duration_ns) override {
    if (duration_ns > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(duration_ns));
  }
};

}  // namespace mallet::input
