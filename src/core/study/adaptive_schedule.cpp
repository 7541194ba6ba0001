#include "core/study/adaptive_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::study {

AdaptiveSchedule::AdaptiveSchedule(const StudyProtocol& protocol, std::string_view participant)
    : protocol_(protocol), seed_(participant_seed(protocol.seed ^ 0xADA97ull, participant)),
      conditions_(protocol.conditions) {
  if (protocol.procedure == StudyProcedure::quest_plus) {
    // One QUEST+ over the pairs' differences, copied per condition: the copies share its
    // likelihood table.
    std::vector<double> stimuli;
    for (const StimulusPair& pair : protocol.pairs) stimuli.push_back(pair.difference_pct);
    const QuestPlus fresh(protocol.adaptive.quest_plus, std::move(stimuli));
    tracks_.assign(conditions_.size(), fresh);
    return;
  }
  for (std::size_t i = 0; i < conditions_.size(); ++i) {
    if (protocol.procedure == StudyProcedure::staircase) tracks_.emplace_back(Staircase(protocol.adaptive.staircase));
    else tracks_.emplace_back(Quest(protocol.adaptive.quest_model, protocol.adaptive.quest_prior));
  }
}

bool AdaptiveSchedule::done(const Track& track) const {
  if (const auto* s = std::get_if<Staircase>(&track)) return s->done();
  if (const auto* p = std::get_if<QuestPlus>(&track)) return p->trials() >= protocol_.adaptive.quest_plus_trials;
  return std::get<Quest>(track).trials() >= protocol_.adaptive.quest_trials;
}

double AdaptiveSchedule::level(const Track& track) const {
  if (const auto* s = std::get_if<Staircase>(&track)) return s->level();
  if (const auto* p = std::get_if<QuestPlus>(&track)) return p->level();
  return std::get<Quest>(track).level();
}

int AdaptiveSchedule::item_of(double level_pct) const {
  const double k = std::round((level_pct - protocol_.adaptive.min_pct) / kAdaptiveGridPct);
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(protocol_.pairs.size() - 1)));
}

int AdaptiveSchedule::max_trials() const {
  const int per_track = protocol_.procedure == StudyProcedure::staircase  ? protocol_.adaptive.staircase.max_trials
                        : protocol_.procedure == StudyProcedure::quest_plus ? protocol_.adaptive.quest_plus_trials
                                                                            : protocol_.adaptive.quest_trials;
  return per_track * static_cast<int>(tracks_.size());
}

std::optional<ScheduledTrial> AdaptiveSchedule::next() const {
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < tracks_.size(); ++i)
    if (!done(tracks_[i])) open.push_back(i);
  if (open.empty()) return std::nullopt;
  ScheduledTrial t;
  t.number = trials_ + 1;
  SplitMix64 rng(seed_ ^ (static_cast<std::uint64_t>(t.number) * 0x9E3779B97F4A7C15ull));
  const std::size_t track = open[rng.below(open.size())];
  t.condition = conditions_[track];
  t.item = item_of(level(tracks_[track]));
  t.swapped = rng.below(2) == 1;
  return t;
}

void AdaptiveSchedule::record(const ScheduledTrial& trial, bool correct) {
  ++trials_;
  for (std::size_t i = 0; i < conditions_.size(); ++i) {
    if (conditions_[i] != trial.condition) continue;
    if (auto* s = std::get_if<Staircase>(&tracks_[i]))
      s->answer(correct, protocol_.pairs.at(static_cast<std::size_t>(trial.item)).difference_pct);
    else if (auto* p = std::get_if<QuestPlus>(&tracks_[i])) p->answer_index(static_cast<std::size_t>(trial.item), correct);
    else std::get<Quest>(tracks_[i]).answer(protocol_.pairs.at(static_cast<std::size_t>(trial.item)).difference_pct, correct);
  }
}

TrackState AdaptiveSchedule::state(StudyCondition condition) const {
  TrackState out;
  for (std::size_t i = 0; i < conditions_.size(); ++i) {
    if (conditions_[i] != condition) continue;
    const Track& track = tracks_[i];
    out.level_pct = protocol_.pairs.at(static_cast<std::size_t>(item_of(level(track)))).difference_pct;
    out.done = done(track);
    if (const auto* s = std::get_if<Staircase>(&track)) {
      out.trials = s->trials();
      out.reversals = s->reversals();
      out.estimate_pct = s->threshold();
    } else if (const auto* p = std::get_if<QuestPlus>(&track)) {
      out.trials = p->trials();
      out.estimate_pct = p->mean().threshold;
      out.estimate_sd_pct = p->sd().threshold;
      out.estimate_mode_pct = p->mode().threshold;
    } else {
      const Quest& q = std::get<Quest>(track);
      out.trials = q.trials();
      out.estimate_pct = q.mean();
      out.estimate_sd_pct = q.sd();
      out.estimate_mode_pct = q.mode();
    }
  }
  return out;
}

}  // namespace mallet::study
