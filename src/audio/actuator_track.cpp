#include "audio/actuator_track.hpp"

#include <algorithm>
#include <limits>

namespace mallet::audio {

ActuatorTrack::ActuatorTrack(const Scene& scene, std::span<const Impact> impacts,
                             const ActuatorConfig& config, int sample_rate_hz)
    : limiter_(config.soft_clip_knee, sample_rate_hz), sample_rate_(sample_rate_hz) {
  for (const Impact& impact : impacts) {
    ActuatorSignal signal(impact, scene.materials.at(impact.material).actuator, config.gain,
                          sample_rate_hz);
    const auto end = signal.end_sample(sample_rate_hz);
    pending_.push_back({signal, end.value_or(std::numeric_limits<std::int64_t>::max())});
  }
  std::stable_sort(pending_.begin(), pending_.end(), [](const Voice& a, const Voice& b) {
    return a.signal.start.index < b.signal.start.index;
  });
}

void ActuatorTrack::render(std::int64_t first, std::span<float> out) {
  const auto count = static_cast<std::int64_t>(out.size());
  const std::int64_t last = first + count;
  while (next_ < pending_.size() && pending_[next_].signal.start.index < last)
    active_.push_back(pending_[next_++]);
  std::erase_if(active_, [&](const Voice& v) { return v.end <= first; });

  mix_.assign(out.size(), 0.0);
  for (const Voice& v : active_) {
    const std::int64_t from = std::max(first, v.signal.start.index);
    const std::int64_t to = std::min(last, v.end);
    for (std::int64_t n = from; n < to; ++n) mix_[n - first] += v.signal.at_sample(n, sample_rate_);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = static_cast<float>(limiter_.tick(mix_[i]));
    clipped_ += limiter_.limiting();
  }
}

}  // namespace mallet::audio
