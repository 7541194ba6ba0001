#include "core/sensitivity_tuner.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mallet {

namespace {

bool is_dot(const IrDot& d) {
  if (d.x == 0 && d.y == 0) return false;  // the spurious (0,0) some remotes report
  return d.x >= 0 && d.x <= 1023 && d.y >= 0 && d.y <= 767;
}

std::string percent(double fraction) { return std::to_string(static_cast<int>(std::lround(fraction * 100))) + " %"; }

}  // namespace

Check validate(const SensitivityTunerConfig& c) {
  if (c.settle_frames < 0) return refused("settle_frames must be >= 0");
  if (c.frames_per_preset < 1) return refused("frames_per_preset must be >= 1");
  if (!(c.min_seen_fraction > 0 && c.min_seen_fraction <= 1)) return refused("min_seen_fraction must be > 0 and <= 1");
  if (!(c.max_spurious_fraction >= 0 && c.max_spurious_fraction < 1))
    return refused("max_spurious_fraction must be >= 0 and < 1");
  if (c.min_size < 0 || c.max_size > 15 || c.min_size > c.max_size)
    return refused("min_size..max_size must be a range within 0..15");
  return {};
}

void observe_frame(SensitivityObservation& o, const IrFrame& frame) {
  int dots = 0;
  int size = -1;
  for (const auto& slot : frame.slots)
    if (slot && is_dot(*slot)) {
      ++dots;
      size = slot->size;
    }
  ++o.frames;
  if (dots >= 1) ++o.frames_seen;
  if (dots >= 2) ++o.frames_spurious;
  if (dots == 1 && size >= 0 && size <= 15) o.sizes.push_back(size);
}

SensitivityVerdict judge(const SensitivityObservation& o, const SensitivityTunerConfig& c) {
  SensitivityVerdict v;
  if (!o.sizes.empty()) {
    std::vector<int> sizes = o.sizes;
    const auto mid = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
    std::nth_element(sizes.begin(), mid, sizes.end());
    v.median_size = *mid;
  }
  if (o.frames <= 0) {
    v.reason = "no frames";
    return v;
  }
  const double frames = o.frames;
  const double seen = o.frames_seen / frames;
  const double spurious = o.frames_spurious / frames;
  if (spurious > c.max_spurious_fraction)
    v.reason = "spurious dots in " + percent(spurious) + " of the frames";
  else if (seen < c.min_seen_fraction)
    v.reason = "the LED was seen in only " + percent(seen) + " of the frames";
  else if (v.median_size >= 0 && (v.median_size < c.min_size || v.median_size > c.max_size))
    v.reason = "dot size " + std::to_string(v.median_size) + " outside " + std::to_string(c.min_size) + ".." +
               std::to_string(c.max_size);
  v.clean = v.reason.empty();
  return v;
}

SensitivityTuner::SensitivityTuner(SensitivityTunerConfig config) : config_(config) {
  if (const Check problem = validate(config_); !problem) throw std::invalid_argument(problem.error());
}

std::string_view SensitivityTuner::preset() const {
  if (done_) return chosen_.value_or(std::string_view{});
  return kSensitivityPresets[index_].name;
}

TunerStep SensitivityTuner::observe(const IrFrame& frame) {
  if (done_) return chosen_ ? TunerStep::chosen : TunerStep::failed;
  if (settled_ < config_.settle_frames) {
    ++settled_;
    return TunerStep::observing;
  }
  observe_frame(current_, frame);
  if (current_.frames < config_.frames_per_preset) return TunerStep::observing;
  return conclude(current_);
}

TunerStep SensitivityTuner::observe(const SensitivityObservation& observation) {
  if (done_) return chosen_ ? TunerStep::chosen : TunerStep::failed;
  return conclude(observation);
}

TunerStep SensitivityTuner::conclude(const SensitivityObservation& observation) {
  const std::string_view name = kSensitivityPresets[index_].name;
  tried_.push_back({name, judge(observation, config_)});
  current_ = {};
  settled_ = 0;
  if (tried_.back().verdict.clean) {
    done_ = true;
    chosen_ = name;
    return TunerStep::chosen;
  }
  if (++index_ < kSensitivityPresets.size()) return TunerStep::next_preset;
  done_ = true;
  return TunerStep::failed;
}

}  // namespace mallet
