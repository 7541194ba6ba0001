#include "app/kiosk/latency_test.hpp"

#include <cmath>
#include <cstdio>

#include <fmt/printf.h>

#include "core/visitor_language.hpp"
#include "core/journal.hpp"
#include "core/strike_line.hpp"

namespace mallet::app {

void LatencyTest::start(Nanos now, const Scene& scene, audio::AudioEngine& engine) {
  instants_.clear();
  // The first instant far enough ahead that its sound can still be scheduled on time.
  for (int i = 0; i < kPulses; ++i) instants_.push_back(now + (i + 1) * kNanosPerSecond);
  all_ = instants_;
  squares_.clear();
  for (Nanos t : all_) squares_.push_back({t, 0});
  for (Nanos t : instants_) {
    Impact pulse;  // a firm strike on the first bar: a sharp onset on both channels
    pulse.t_ns = t;
    pulse.target = 0;
    pulse.material = scene.targets.empty() ? -1 : scene.targets[0].material;
    pulse.note = scene.targets.empty() ? 0 : scene.targets[0].note;
    pulse.speed_m_per_s = 1.0;
    if (!scene.targets.empty()) engine.post(pulse);  // heard at t: the engine's clock
  }
  journal::notice("latency test: {} pulses, one a second, from {} (square, note and actuator at each)", kPulses,
                  format_seconds(instants_.front()).c_str());
}

bool LatencyTest::square_shown(Nanos present) {
  std::erase_if(instants_, [present](Nanos t) { return present >= t + kShown; });
  bool shown = false;
  for (Nanos t : instants_)
    if (present >= t) shown = true;
  if (shown)
    for (audio::PhotodiodeSquare& s : squares_)
      if (s.present == 0 && present >= s.instant && present < s.instant + kShown) s.present = present;
  return shown;
}

std::string LatencyTest::status(Nanos now) const {
  if (all_.empty() || now >= all_.back() + kDoneShownFor) return {};
  if (now >= all_.back()) return tr("latency test: done");
  int pulse = 0;
  for (Nanos t : all_) pulse += now >= t;
  // Whole seconds, rounded up: the last half second before the pulse is "in 1 s", never "in 0 s".
  if (pulse == 0)
    return fmt::sprintf(tr("latency test: the first pulse in %.0f s"), std::ceil(to_seconds(all_.front() - now)));
  return fmt::sprintf(tr("latency test: pulse %d of %d"), pulse, kPulses);
}

}  // namespace mallet::app
