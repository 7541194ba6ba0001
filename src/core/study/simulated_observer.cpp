#include "core/study/simulated_observer.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "core/study/psychometric_fit.hpp"

namespace mallet::study {

SimulatedObserver::SimulatedObserver(const StudyProtocol& protocol, std::string_view participant)
    : protocol_(protocol), seed_(participant_seed(protocol.seed ^ 0x5EED0B5E7Eull, participant)) {}

double SimulatedObserver::threshold_pct(StudyCondition condition) {
  switch (condition) {
    case StudyCondition::both: return 8.0;
    case StudyCondition::tactile_only: return 12.0;
    case StudyCondition::visual_only: return 20.0;
    case StudyCondition::none: break;
  }
  return std::numeric_limits<double>::infinity();
}

double SimulatedObserver::texture_threshold_pct(StudyCondition condition) {
  switch (condition) {
    case StudyCondition::both: return 20.0;
    case StudyCondition::visual_only: return 25.0;
    case StudyCondition::tactile_only:  // the stripes say where the disc is, not its slope
    case StudyCondition::none: break;
  }
  return std::numeric_limits<double>::infinity();
}

namespace {
//! texture_slope's bump or hole: the Speed technique shows the slope's sign; the stripes alone
//! do not (a guess, as with neither).
double shape_accuracy(StudyCondition condition) {
  switch (condition) {
    case StudyCondition::both: return 0.90;
    case StudyCondition::visual_only: return 0.85;
    case StudyCondition::tactile_only:
    case StudyCondition::none: break;
  }
  return 0.5;
}

double naming_accuracy(StudyCondition condition) {
  switch (condition) {
    case StudyCondition::both: return 0.95;
    case StudyCondition::tactile_only: return 0.85;
    case StudyCondition::visual_only: return 0.70;
    case StudyCondition::none: break;
  }
  return 0.0;
}
}  // namespace

ObserverAnswer SimulatedObserver::respond(const ScheduledTrial& trial) const {
  SplitMix64 rng(seed_ ^ (static_cast<std::uint64_t>(trial.number) * 0xD1B54A32D192ED03ull));
  const double u_answer = rng.unit();
  const double u_time = rng.unit();
  ObserverAnswer out;
  const double rt_ms = 400.0 + 400.0 * u_time + (trial.condition == StudyCondition::none ? 200.0 : 0.0);
  out.response_time = static_cast<Nanos>(rt_ms * 1e6);
  const std::string correct = correct_answer(protocol_, trial);
  if (protocol_.paired()) {
    const double t = protocol_.texture() ? texture_threshold_pct(trial.condition) : threshold_pct(trial.condition);
    const double p = std::isinf(t) ? 0.5 : psychometric_2afc(difference_pct(protocol_, trial), t, kSlopePerPct);
    out.answer = u_answer < p ? correct : (correct == "1" ? "2" : "1");
    return out;
  }
  std::vector<std::string> choices = protocol_.answer_choices();
  if (protocol_.texture()) {
    out.answer = u_answer < shape_accuracy(trial.condition) ? correct : correct == "bump" ? "hole" : "bump";
    return out;
  }
  if (u_answer < naming_accuracy(trial.condition)) {
    out.answer = correct;
    return out;
  }
  if (trial.condition != StudyCondition::none && choices.size() > 1)
    std::erase(choices, correct);  // a wrong answer is one of the others
  out.answer = choices[rng.below(choices.size())];
  return out;
}

}  // namespace mallet::study
