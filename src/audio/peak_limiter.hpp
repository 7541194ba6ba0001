#pragma once
// A zero-latency peak limiter for one signal (the speaker's or the actuator's), so that no
// volume or gain setting can drive a channel to full scale.
//
// WHY ZERO LATENCY. A look-ahead limiter would delay every sample by its look-ahead; the
// engine promises that each impact lands on its own sample (and, with schedule_ahead_ms,
// after exactly that constant latency), and the actuator's Eq. 1 is measured against the
// exact formula at that sample. So the gain is computed from the current sample and the
// past only: nothing is delayed, the engine's timing is what it was without the limiter.
// The price of no look-ahead is that the gain drops within the sample that exceeds the
// threshold (instant attack): the first rising edge of an over takes the soft shoulder's
// shape (as the old per-sample soft clip did); after it the gain is held, then released
// smoothly, so the rest of the note keeps its waveform at a lower level instead of being
// flattened.
//
// HOW. A peak envelope e follows |x| up at once, holds kHoldS, then falls exponentially
// (time constant kReleaseS). The gain is g = s(e)/e, where s is soft_clip's tanh shoulder
// from the threshold to the ceiling (slope 1 at the threshold, so g is continuous and is
// 1 at e = threshold). Since |x| ≤ e, |x·g| ≤ s(e) < ceiling; a final clamp makes the bound
// hold under rounding too, and for ±inf; NaN is output as 0.
//
// BELOW THE THRESHOLD the output is the input, bit for bit: a signal whose |x| never
// exceeded the threshold, or whose last over is more than the hold plus the release back
// to the threshold ago, passes unchanged (Eq. 1 at sane gains, research stimuli).
//
// Real-time safe: no allocation, no locks, no exceptions after construction; a few flops a
// sample (a tanh and a division only while limiting). No buffers: nothing is delayed.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/app_config.hpp"
#include "core/soft_clip.hpp"

namespace mallet::audio {

class PeakLimiter {
 public:
  //! The highest magnitude either channel ever gets: 0.98 (−0.18 dBFS), 1.9 % below full
  //! scale. A float, so that the double-to-float conversion of the output cannot round above
  //! it. High enough for the actuator's soft_clip_knee (up to 0.95) to keep a shoulder.
  static constexpr double kCeiling = 0.98f;
  //! How long the gain is held after a peak: half a period at 25 Hz, so the peaks of a
  //! sinusoid down to 25 Hz refresh the envelope before it falls (no gain ripple per cycle).
  static constexpr double kHoldS = 0.020;
  static constexpr double kReleaseS = 0.100;  //!< time constant of the gain's recovery
  static_assert(kMaxSoftClipKnee < kCeiling, "the settings' highest soft_clip_knee must stay under the ceiling");

  //! Throws std::invalid_argument unless 0 < threshold < ceiling ≤ 1 and the rate is positive.
  PeakLimiter(double threshold, int sample_rate_hz, double ceiling = kCeiling)
      : threshold_(threshold), ceiling_(ceiling) {
    if (!(threshold > 0 && threshold < ceiling && ceiling <= 1.0))
      throw std::invalid_argument("audio: the limiter's threshold must be above 0 and below its ceiling");
    if (sample_rate_hz <= 0) throw std::invalid_argument("audio: the limiter needs a positive sample rate");
    hold_ = static_cast<std::int64_t>(std::ceil(kHoldS * sample_rate_hz));
    release_ = std::exp(-1.0 / (kReleaseS * sample_rate_hz));
  }

  //! One sample through the limiter.
  double tick(double x) {
    double a = std::fabs(x);
    if (!(a <= kMaxEnvelope)) {  // NaN or beyond any real signal (±inf)
      if (std::isnan(x)) return 0.0;
      a = kMaxEnvelope;
    }
    if (a >= envelope_) {
      envelope_ = a;
      hold_left_ = hold_;
    } else if (hold_left_ > 0) {
      --hold_left_;
    } else {
      envelope_ = std::max(envelope_ * release_, a);  // never below the sample itself
    }
    if (envelope_ <= threshold_) {
      envelope_ = 0.0;  // the gain is 1 from here until a sample above the threshold
      return x;
    }
    const double gain = soft_clip(envelope_, threshold_, ceiling_) / envelope_;
    return std::clamp(x * gain, -ceiling_, ceiling_);
  }

  //! True when the last sample was turned down (its gain was below 1).
  bool limiting() const { return envelope_ > threshold_; }
  //! The gain applied to the last sample (1 when not limiting).
  double gain() const { return limiting() ? soft_clip(envelope_, threshold_, ceiling_) / envelope_ : 1.0; }

 private:
  static constexpr double kMaxEnvelope = 1e12;

  double threshold_, ceiling_;
  std::int64_t hold_ = 0, hold_left_ = 0;
  double release_ = 0.0;
  double envelope_ = 0.0;
};

}  // namespace mallet::audio
