#include "core/study/balanced_schedule.hpp"

#include <cmath>
#include <utility>

namespace mallet::study {

std::uint64_t participant_seed(std::uint64_t protocol_seed, std::string_view participant) {
  std::uint64_t h = 0xCBF29CE484222325ull;
  for (unsigned char c : participant) {
    h ^= c;
    h *= 0x100000001B3ull;
  }
  SplitMix64 mix(protocol_seed ^ h);
  return mix.next();
}

std::vector<ScheduledTrial> balanced_schedule(const StudyProtocol& protocol, std::string_view participant) {
  std::vector<ScheduledTrial> trials;
  const bool two_afc = protocol.paired();
  for (StudyCondition c : protocol.conditions)
    for (std::size_t item = 0; item < protocol.items(); ++item)
      for (int r = 0; r < protocol.repetitions; ++r)
        trials.push_back({0, c, static_cast<int>(item), two_afc && r % 2 == 1});
  SplitMix64 rng(participant_seed(protocol.seed, participant));
  for (std::size_t i = trials.size(); i > 1; --i) std::swap(trials[i - 1], trials[rng.below(i)]);
  for (std::size_t i = 0; i < trials.size(); ++i) trials[i].number = static_cast<int>(i + 1);
  return trials;
}

std::vector<int> shown_stimuli(const StudyProtocol& protocol, const ScheduledTrial& trial) {
  if (!protocol.paired()) return {protocol.named.at(static_cast<std::size_t>(trial.item))};
  const StimulusPair& p = protocol.pairs.at(static_cast<std::size_t>(trial.item));
  return trial.swapped ? std::vector<int>{p.b, p.a} : std::vector<int>{p.a, p.b};
}

std::string stimuli_text(const StudyProtocol& protocol, const ScheduledTrial& trial) {
  std::string out;
  for (int s : shown_stimuli(protocol, trial)) {
    if (!out.empty()) out += '|';
    out += protocol.stimuli[static_cast<std::size_t>(s)].name;
  }
  return out;
}

std::string correct_answer(const StudyProtocol& protocol, const ScheduledTrial& trial) {
  const std::vector<int> shown = shown_stimuli(protocol, trial);
  const Stimulus& first = protocol.stimuli[static_cast<std::size_t>(shown[0])];
  if (!protocol.paired()) return first.relief ? to_string(first.relief->shape) : first.material.name;
  const int harder = protocol.pairs[static_cast<std::size_t>(trial.item)].harder;
  return shown[0] == harder ? "1" : "2";
}

double difference_pct(const StudyProtocol& protocol, const ScheduledTrial& trial) {
  if (!protocol.paired()) return std::nan("");
  return protocol.pairs.at(static_cast<std::size_t>(trial.item)).difference_pct;
}

}  // namespace mallet::study
