#pragma once
// The actuator channel rendered offline from a list of impacts: each impact's Eq. 1
// signal starts at its own sample (sub-sample exact phase), overlapping strikes add,
// and the sum passes the engine's output limiter (peak_limiter.hpp). This is the
// reference the real-time engine is measured against; it evaluates Eq. 1 directly (exp
// and sin per sample), which is exact but not the cheapest way.
#include <cstdint>
#include <span>
#include <vector>

#include "audio/peak_limiter.hpp"
#include "core/actuator_signal.hpp"
#include "core/app_config.hpp"
#include "core/scene.hpp"

namespace mallet::audio {

class ActuatorTrack {
 public:
  ActuatorTrack(const Scene& scene, std::span<const Impact> impacts, const ActuatorConfig& config,
                int sample_rate_hz);

  //! Writes samples [first, first + out.size()) of the channel; call with increasing
  //! `first` (voices that have finished are retired as the render moves on).
  void render(std::int64_t first, std::span<float> out);

  std::uint64_t clipped_samples() const { return clipped_; }  //!< samples the limiter turned down

 private:
  struct Voice {
    ActuatorSignal signal;
    std::int64_t end;  //!< INT64_MAX when undamped
  };

  std::vector<Voice> pending_;  //!< sorted by start sample
  std::size_t next_ = 0;
  std::vector<Voice> active_;
  PeakLimiter limiter_;
  int sample_rate_;
  std::uint64_t clipped_ = 0;
  std::vector<double> mix_;
};

}  // namespace mallet::audio
