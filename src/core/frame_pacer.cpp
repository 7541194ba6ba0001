#include "core/frame_pacer.hpp"

#include <cerrno>
#include <cmath>
#include <ctime>

namespace mallet {

FramePacer::FramePacer(double max_fps) { set_max_fps(max_fps); }

void FramePacer::set_max_fps(double max_fps) {
  max_fps_ = max_fps > 0 && std::isfinite(max_fps) ? max_fps : 0;
  period_ns_ = max_fps_ > 0 ? static_cast<Nanos>(std::llround(1e9 / max_fps_)) : 0;
  next_ = -1;
}

Nanos FramePacer::begin(Nanos now) {
  if (period_ns_ == 0) return now;
  if (next_ < 0 || now >= next_ + period_ns_) next_ = now;  // the first frame, or a whole period late
  const Nanos at = now > next_ ? now : next_;
  next_ += period_ns_;
  return at;
}

void sleep_until_monotonic(Nanos t) {
  if (t <= 0) return;
  timespec ts{static_cast<time_t>(t / kNanosPerSecond), static_cast<long>(t % kNanosPerSecond)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace mallet
