#pragma once
// Impact → first output sample: where in the output stream an impact lands, relative to
// its own time, for random impact times. Sample arithmetic on the engine's own clock, so
// the figures are exact, not wall time (`bench audio` and `bench report` print them).
#include <random>

#include "core/app_config.hpp"
#include "core/scene.hpp"

namespace mallet::app {

struct FirstSampleLatency {
  double worst_ms = 0;
  double best_ms = 1e9;
};

//! Posts `impacts` strikes of `scene`'s bar `target`, each dated somewhere in the block
//! before the one it is posted in (uniformly, drawn from `rng`), through an engine built
//! from `config` at `rate_hz` that processes `block` frames at a time; measures from each
//! impact's time to its first non-zero actuator sample, letting every voice retire before
//! the next impact.
FirstSampleLatency first_sample_latency(const Scene& scene, const AppConfig& config, int rate_hz, int block,
                                        int target, int impacts, std::mt19937& rng);

}  // namespace mallet::app
