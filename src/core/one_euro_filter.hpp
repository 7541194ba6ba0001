#pragma once
// The 1€ filter for the 2-D pointer: G. Casiez, N. Roussel, D. Vogel, "1€ Filter: A Simple
// Speed-based Low-pass Filter for Noisy Input in Interactive Systems", CHI 2012,
// pp. 2527–2530, doi:10.1145/2207676.2208639.
//
// A first-order low-pass filter whose cutoff rises with the pointer's speed: a still hand
// is smoothed hard (jitter goes), a fast one lightly (lag goes):
//     cutoff_hz = min_cutoff_hz + beta_per_m · |dx̂/dt|
//     alpha(fc, dt) = 1 / (1 + τ/dt),  τ = 1 / (2π fc)
//     x̂ᵢ = alpha · xᵢ + (1 − alpha) · x̂ᵢ₋₁
// The speed is the raw sample's difference from the *filtered* previous value,
// (xᵢ − x̂ᵢ₋₁) / dt, itself low-passed at d_cutoff_hz — as the widely copied Python
// reference (jaantollander/OneEuroFilter) does. The authors' original C++ code
// (OneEuroFilter.cc, `x->lastRawValue()`) takes it from the *raw* previous sample instead,
// (xᵢ − xᵢ₋₁) / dt; `derivative_from_raw` selects that. They differ in motion: from the
// filtered value the estimate includes the lag (it reads v/α on a ramp, not v), which
// raises the cutoff sooner and so cuts lag further; from the raw value it is the true
// speed, noisier at rest. `mallet bench input` measures both.
//
// Two dimensions, one cutoff: the speed is the magnitude of the 2-D derivative, so a
// diagonal stroke is filtered exactly like a horizontal one (filtering x and y apart, as
// the 1-D reference would, lets the slow axis of a diagonal stroke lag behind).
//
// Units: positions in metres (the world plane the contact solver works in), so the speed
// is in m/s and beta in 1/m. The filter works for any unit; beta then scales inversely.
// dt comes from the int64 nanosecond timestamps (differences only: weeks of uptime change
// nothing). A sample with a non-finite position or a time not after the previous one is
// ignored and counted; the output is never NaN.
#include <cstdint>
#include <optional>
#include <string>

#include "core/geometry.hpp"
#include "core/pointer_sample.hpp"
#include "core/result.hpp"
#include "core/time.hpp"

namespace mallet {

//! Defaults chosen by `mallet bench input` (Wii camera model: 0.82 mm/px, σ 0.5 px, 100 Hz):
//! still-cursor jitter 0.18 mm (raw 0.48 mm), lag 0.9 ms in strikes and 4 ms while aiming.
struct OneEuroConfig {
  double min_cutoff_hz = 1.0;  //!< cutoff of a still pointer: lower = less jitter, more slow-motion lag
  double beta_per_m = 500.0;   //!< cutoff rise per m/s of speed: higher = less lag in fast motion
  double d_cutoff_hz = 1.0;    //!< cutoff of the speed estimate (the paper's 1 Hz)
  bool derivative_from_raw = false;  //!< speed from the raw previous sample (C++ reference)
};

//! Passes when `config` is usable; otherwise fails with one line naming the bad key and why.
Check validate(const OneEuroConfig& config);

class OneEuroFilter {
 public:
  using Counters = SampleCounters;

  //! Throws std::invalid_argument when validate(config) fails.
  explicit OneEuroFilter(OneEuroConfig config = {});

  //! Feeds a raw sample; returns the filtered position (the last one if this sample was
  //! ignored), or nothing before the first accepted sample.
  std::optional<Vec2> update(Nanos t_ns, Vec2 raw);

  //! The filtered position after the last accepted sample.
  std::optional<Vec2> value() const;
  //! The filter's speed estimate (the low-passed derivative), m/s; zero before two samples.
  Vec2 velocity() const { return dx_; }
  //! The cutoff used for the last accepted sample.
  double last_cutoff_hz() const { return last_cutoff_hz_; }

  const OneEuroConfig& config() const { return config_; }
  const Counters& counters() const { return counters_; }

  //! Forgets the state (e.g. tracking was lost): the next sample passes through unfiltered.
  //! Counters are kept.
  void reset();

 private:
  OneEuroConfig config_;
  bool primed_ = false;
  Nanos t_ns_ = 0;
  Vec2 x_{};   //!< filtered position
  Vec2 raw_{}; //!< previous raw sample
  Vec2 dx_{};  //!< filtered derivative
  double last_cutoff_hz_ = 0;
  Counters counters_;
};

//! The smoothing factor of a first-order low-pass at `cutoff_hz` for a step of `dt_s`.
double one_euro_alpha(double cutoff_hz, double dt_s);

}  // namespace mallet
