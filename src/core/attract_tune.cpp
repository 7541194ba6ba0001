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

namespace {
constexpr double kSweepReach = 1.6;  // the sweep starts and ends this many radii from the centre
constexpr double kSweepRest_s = 1.5;

double sweep_length(const TextureRelief& r) { return 2 * kSweepReach * r.radius_m; }
}  // namespace

std::vector<PointerSample> attract_sweep(const Scene& scene, Nanos start_ns, double rate_hz, double speed) {
  std::vector<PointerSample> out;
  if (!scene.texture || !(rate_hz > 0) || !(speed > 0)) return out;
  const TextureRelief& r = scene.texture->relief;
  const double leg_s = sweep_length(r) / speed;
  const double total_s = 2 * leg_s;
  const auto n = static_cast<std::int64_t>(std::floor(total_s * rate_hz));
  for (std::int64_t k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    const bool back = t > leg_s;
    const double along = (back ? total_s - t : t) * speed;  // 0 .. length
    PointerSample s;
    s.t_ns = start_ns + static_cast<Nanos>(std::llround(t * 1e9));
    s.x = r.center.x - kSweepReach * r.radius_m + along;
    s.y = r.center.y + (back ? 0.3 * r.radius_m : 0.0);
    out.push_back(s);
  }
  return out;
}

Nanos attract_sweep_period(const Scene& scene, double speed) {
  if (!scene.texture || !(speed > 0)) return 0;
  return static_cast<Nanos>(std::llround((2 * sweep_length(scene.texture->relief) / speed + kSweepRest_s) * 1e9));
}

}  // namespace mallet
