#include "app/bench/first_sample_latency.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "audio/audio_setup.hpp"
#include "core/impact.hpp"

namespace mallet::app {

FirstSampleLatency first_sample_latency(const Scene& scene, const AppConfig& config, int rate_hz, int block,
                                        int target, int impacts, std::mt19937& rng) {
  audio::AudioRig rig = audio::make_audio_rig(scene, config, rate_hz);
  std::vector<float> out(static_cast<std::size_t>(2 * block));
  std::uniform_real_distribution<double> within(0.0, 1.0);
  const Target& bar = scene.targets[static_cast<std::size_t>(target)];
  FirstSampleLatency latency;
  for (int k = 0; k < impacts; ++k) {
    // The impact happened somewhere in the previous block and is posted now.
    const std::int64_t start = rig.engine->position();
    const Nanos t = static_cast<Nanos>((static_cast<double>(start) - within(rng) * block) / rate_hz * 1e9);
    Impact i;
    i.t_ns = t;
    i.target = target;
    i.material = bar.material;
    i.note = bar.note;
    i.speed_m_per_s = 1.0;
    rig.engine->post(i);
    std::int64_t first = -1;
    for (int b = 0; b < 4000 && first < 0; ++b) {
      const std::int64_t base = rig.engine->position();
      rig.engine->process(out.data(), block);
      for (int f = 0; f < block && first < 0; ++f)
        if (out[static_cast<std::size_t>(2 * f + 1)] != 0.0f) first = base + f;
    }
    const double ms = (static_cast<double>(first) / rate_hz - static_cast<double>(t) * 1e-9) * 1e3;
    latency.worst_ms = std::max(latency.worst_ms, ms);
    latency.best_ms = std::min(latency.best_ms, ms);
    // Let every voice retire (bounded), so the next impact's first sample is its own.
    for (int b = 0; b < 100000 && rig.engine->counters().active_voices > 0; ++b) rig.engine->process(out.data(), block);
  }
  return latency;
}

}  // namespace mallet::app
