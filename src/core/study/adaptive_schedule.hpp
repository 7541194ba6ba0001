#pragma once
// The trials of an adaptive protocol (procedure = "staircase", "quest" or "quest_plus"),
// decided one at a time from the answers so far. Each condition has its own track, a
// Staircase, a Quest or a QuestPlus (whose stimuli are the protocol's pairs),
// and the tracks are interleaved: trial N's condition is drawn among the tracks not yet done,
// and the order of its two taps, from the participant's seed and N (SplitMix64, as the
// balanced schedule draws). A track's level is the pair of the protocol's grid nearest to it.
// Everything is a function of the protocol, the participant and the answers: a session
// resumed after a crash replays its rows (record) and asks next() where it stopped.
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/study/balanced_schedule.hpp"
#include "core/study/quest.hpp"
#include "core/study/quest_plus.hpp"
#include "core/study/staircase.hpp"
#include "core/study/study_protocol.hpp"

namespace mallet::study {

//! A track's state after a trial, as the results row records it.
struct TrackState {
  double level_pct = 0;          //!< the difference its next trial tests
  int trials = 0;                //!< answered in this track
  int reversals = -1;            //!< staircase; −1 for QUEST and QUEST+
  //! staircase: mean of the last reversals; QUEST: posterior mean; QUEST+: the posterior mean
  //! of the threshold
  std::optional<double> estimate_pct;
  std::optional<double> estimate_sd_pct;  //!< QUEST: posterior SD; QUEST+: the threshold's marginal SD
  std::optional<double> estimate_mode_pct;  //!< QUEST: posterior mode; QUEST+: the joint mode's threshold
  bool done = false;
};

class AdaptiveSchedule {
 public:
  AdaptiveSchedule(const StudyProtocol& protocol, std::string_view participant);

  //! The next trial; nothing when every track is done.
  std::optional<ScheduledTrial> next() const;
  //! The answer of `trial` (the one next() gave).
  void record(const ScheduledTrial& trial, bool correct);
  TrackState state(StudyCondition condition) const;
  //! Trials recorded so far.
  int trials() const { return trials_; }
  //! The most trials the tracks can take together (their stop rules' caps).
  int max_trials() const;

 private:
  using Track = std::variant<Staircase, Quest, QuestPlus>;
  const StudyProtocol& protocol_;
  std::uint64_t seed_;
  std::vector<StudyCondition> conditions_;
  std::vector<Track> tracks_;  //!< one per condition, in protocol order
  int trials_ = 0;
  bool done(const Track& track) const;
  double level(const Track& track) const;
  //! The pair of the grid nearest `level_pct`.
  int item_of(double level_pct) const;
};

}  // namespace mallet::study
