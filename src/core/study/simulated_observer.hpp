#pragma once
// The documented stand-in for a participant, so that a whole protocol runs headless in a
// test. Its answers depend only on (protocol seed, participant ID, trial number): a
// resumed session gets the same answers as an uninterrupted one.
//   2AFC: P(correct) = 0.5 + 0.5/(1 + e^(−0.25·(x − T))), x the pair's difference in B (%),
//         T = 8 % (both), 12 % (tactile_only), 20 % (visual_only); "none" guesses (0.5).
//   name_material: correct with 0.95 (both), 0.85 (tactile_only), 0.70 (visual_only),
//         otherwise (and always in "none") a uniform guess among the other materials
//         (in "none", among all of them).
//   texture_slope (the visual cue is the Speed technique, the tactile one the stripes, which
//         show where the disc is but not its slope): "steeper" as 2AFC above with T = 20 %
//         (both), 25 % (visual_only), chance otherwise; "bump or hole" correct with 0.90
//         (both), 0.85 (visual_only), a guess otherwise.
//   Response time: 400–800 ms after the answer window opens, +200 ms in "none".
#include <string>
#include <string_view>

#include "core/study/balanced_schedule.hpp"
#include "core/study/study_protocol.hpp"

namespace mallet::study {

struct ObserverAnswer {
  std::string answer;
  Nanos response_time = 0;
};

class SimulatedObserver {
 public:
  static constexpr double kSlopePerPct = 0.25;

  SimulatedObserver(const StudyProtocol& protocol, std::string_view participant);

  ObserverAnswer respond(const ScheduledTrial& trial) const;
  //! The observer's 75 % threshold in a condition (percent difference in B); none: infinite.
  static double threshold_pct(StudyCondition condition);
  //! The same for texture_slope's "steeper" (percent difference in the reliefs' height).
  static double texture_threshold_pct(StudyCondition condition);

 private:
  const StudyProtocol& protocol_;
  std::uint64_t seed_;
};

}  // namespace mallet::study
