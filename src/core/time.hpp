#pragma once
// One clock for the whole program: int64 nanoseconds on a monotonic time base.
// Time is never accumulated in floating point (a kiosk runs for weeks); a double
// appears only for a *difference* of two such values, e.g. time since an impact.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>

namespace mallet {

using Nanos = std::int64_t;

inline constexpr Nanos kNanosPerSecond = 1'000'000'000;

//! Seconds (double) of a nanosecond difference, exact to the nanosecond for any span
//! the program meets: the whole seconds and the remainder are converted separately.
constexpr double to_seconds(Nanos dt) {
  const Nanos whole = dt / kNanosPerSecond;
  const Nanos rest = dt % kNanosPerSecond;
  return static_cast<double>(whole) + static_cast<double>(rest) * 1e-9;
}

//! Nearest nanosecond count of `seconds`, or nothing if it is not finite or does not
//! fit in int64 (about ±292 years).
inline std::optional<Nanos> from_seconds(double seconds) {
  if (!std::isfinite(seconds) || std::fabs(seconds) > 9.2e9) return std::nullopt;
  return static_cast<Nanos>(std::llround(seconds * 1e9));
}

//! Now on the program's clock (std::chrono::steady_clock, i.e. CLOCK_MONOTONIC).
inline Nanos monotonic_now() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace mallet
