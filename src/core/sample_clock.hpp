#pragma once
// Where an event on the nanosecond clock lands on an audio sample grid: the first
// sample at or after it, and how far after the event that sample is. Integer
// arithmetic only, so an impact at any uptime lands on its own sample.
#include "core/time.hpp"

namespace mallet {

struct SampleAlignment {
  std::int64_t index = 0;    //!< first sample n with n/fs >= t
  double delay_s = 0.0;      //!< n/fs − t, in [0, 1/fs)
};

constexpr SampleAlignment align_to_sample(Nanos t_ns, int sample_rate_hz) {
  // t = q·1e9 + r with 0 <= r < 1e9 (floor division, valid for negative t too).
  Nanos q = t_ns / kNanosPerSecond;
  Nanos r = t_ns % kNanosPerSecond;
  if (r < 0) {
    r += kNanosPerSecond;
    --q;
  }
  const std::int64_t fs = sample_rate_hz;
  const std::int64_t scaled = r * fs;  // < 1e9 · 1e6: no overflow for any real rate
  const std::int64_t within = (scaled + kNanosPerSecond - 1) / kNanosPerSecond;  // ceil
  const std::int64_t remainder_ns_fs = within * kNanosPerSecond - scaled;        // [0, 1e9)
  return {q * fs + within,
          static_cast<double>(remainder_ns_fs) / (static_cast<double>(fs) * 1e9)};
}

//! Seconds between sample `n` and an event aligned as `a` (n >= a.index).
constexpr double seconds_since(const SampleAlignment& a, std::int64_t n, int sample_rate_hz) {
  return static_cast<double>(n - a.index) / sample_rate_hz + a.delay_s;
}

//! The time `frames` samples take, in whole nanoseconds (truncated), exact for any count.
constexpr Nanos frames_to_ns(std::int64_t frames, int sample_rate_hz) {
  return (frames / sample_rate_hz) * kNanosPerSecond + (frames % sample_rate_hz) * kNanosPerSecond / sample_rate_hz;
}

}  // namespace mallet
