#include "core/attract_tune.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace mallet {
namespace {

//! One note: its degree (bar of the row from C), how many beats until the next, and how
//! hard it is struck (a factor of the tune's speed).
struct Note {
  int degree;
  double beats;
  double dynamic;
};

// The first line of "Ode to Joy": rising to the G, falling back, a breath, and the closing
// half-cadence, its last note held.
constexpr Note kOdeToJoy[] = {{2, 1, 0.8}, {2, 1, 0.9}, {3, 1, 1.0}, {4, 1, 1.3},  {4, 1, 1.6},
                              {3, 1, 1.2}, {2, 1, 1.0}, {1, 1, 0.8}, {0, 1, 0.6},  {0, 1, 0.7},
                              {1, 1, 0.9}, {2, 1, 1.1}, {2, 1.5, 1.4}, {1, 1, 0.8}, {1, 2, 0.6}};
// "Twinkle, Twinkle, Little Star", its first two lines: soft, up to the A, down to the tonic.
constexpr Note kTwinkle[] = {{0, 1, 0.6}, {0, 1, 0.6}, {4, 1, 1.0}, {4, 1, 1.1}, {5, 1, 1.4},
                             {5, 1, 1.5}, {4, 2, 1.2}, {3, 1, 0.9}, {3, 1, 0.9}, {2, 1, 0.8},
                             {2, 1, 0.8}, {1, 1, 0.7}, {1, 1, 0.6}, {0, 2, 0.5}};

struct Tune {
  const Note* notes;
  std::size_t size;
};
constexpr Tune kTunes[] = {{kOdeToJoy, std::size(kOdeToJoy)}, {kTwinkle, std::size(kTwinkle)}};

Nanos beats(double n, const AttractTune& tune) { return static_cast<Nanos>(std::llround(n * tune.beat_s * 1e9)); }

}  // namespace

std::vector<ScriptedStrike> attract_phrase(const Scene& scene, Nanos start_ns, const AttractTune& tune) {
  std::vector<ScriptedStrike> strikes;
  double beat = 0;
  std::size_t played = 0;
  for (const Instrument& inst : scene.instruments) {
    if (inst.targets.empty()) continue;
    const Tune& t = kTunes[played++ % std::size(kTunes)];
    for (std::size_t i = 0; i < t.size; ++i) {
      const Note& n = t.notes[i];
      const int bar = inst.targets[std::min<std::size_t>(static_cast<std::size_t>(n.degree), inst.targets.size() - 1)];
      strikes.push_back({bar, start_ns + beats(beat, tune), tune.speed_m_per_s * n.dynamic});
      beat += n.beats;
    }
    beat += 1;  // a breath between the instruments, for the travel
  }
  return strikes;
}

Nanos attract_period(const Scene& scene, const AttractTune& tune) {
  double total = 0;
  std::size_t played = 0;
  for (const Instrument& inst : scene.instruments) {
    if (inst.targets.empty()) continue;
    const Tune& t = kTunes[played++ % std::size(kTunes)];
    for (std::size_t i = 0; i < t.size; ++i) total += t.notes[i].beats;
    total += 1;
  }
  return beats(total + tune.rest_beats, tune);
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
