#include "core/attract_tune.hpp"

#include <cmath>

namespace mallet {
namespace {

constexpr int kDegrees[] = {0, 2, 4, 7, 4};

Nanos beats(double n, const AttractTune& tune) { return static_cast<Nanos>(std::llround(n * tune.beat_s * 1e9)); }

}  // namespace

std::vector<ScriptedStrike> attract_phrase(const Scene& scene, Nanos start_ns, const AttractTune& tune) {
  std::vector<ScriptedStrike> strikes;
  int step = 0;
  for (const Instrument& inst : scene.instruments) {
    if (inst.targets.empty()) continue;
    for (int degree : kDegrees) {
      const int bar = inst.targets[std::min<std::size_t>(degree, inst.targets.size() - 1)];
      strikes.push_back({bar, start_ns + beats(step++, tune), tune.speed_m_per_s});
    }
    ++step;  // a breath between the instruments, for the travel
  }
  return strikes;
}

Nanos attract_period(const Scene& scene, const AttractTune& tune) {
  std::size_t n = 0;
  for (const Instrument& inst : scene.instruments)
    if (!inst.targets.empty()) n += std::size(kDegrees) + 1;
  return beats(static_cast<double>(n) + tune.rest_beats, tune);
}

}  // namespace mallet
