#include "core/study/trial_timeline.hpp"

namespace mallet::study {

TrialTimeline::TrialTimeline(const StudyTiming& timing, Nanos start, int stimuli)
    : timing_(timing), start_(start), stimuli_(stimuli < 1 ? 1 : stimuli) {}

std::optional<int> TrialTimeline::showing(Nanos now) const {
  for (int k = 0; k < stimuli_; ++k)
    if (now >= onset(k) && now < onset(k) + timing_.stimulus) return k;
  return std::nullopt;
}

TrialTimeline::Phase TrialTimeline::phase(Nanos now) const {
  if (answered_at_ && now >= *answered_at_) return Phase::done;
  if (now < onset(0)) return Phase::waiting;
  if (showing(now)) return Phase::stimulus;
  if (now < answer_opens()) return Phase::gap;
  return Phase::answer;
}

std::optional<Nanos> TrialTimeline::answer(Nanos t) {
  if (answered_at_ || t < answer_opens()) return std::nullopt;
  answered_at_ = t;
  response_ = t - answer_opens();
  return response_;
}

std::optional<Nanos> TrialTimeline::next_start() const {
  if (!answered_at_) return std::nullopt;
  return *answered_at_ + timing_.inter_trial;
}

}  // namespace mallet::study
