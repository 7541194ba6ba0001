#pragma once
// One trial on the int64 ns clock, as a small state machine:
//   waiting (lead) → stimulus 1 → [gap → stimulus 2] → answer → done
// Stimulus k starts at start + lead + k·stimulus_interval and is shown for `stimulus`;
// the answer window opens when the last one is over. An answer before that is not an
// answer (a key pressed during a stimulus is ignored, as in the usual 2AFC procedure);
// the response time runs from the window's opening. The next trial starts `inter_trial`
// after the answer.
#include <optional>

#include "core/study/study_protocol.hpp"

namespace mallet::study {

class TrialTimeline {
 public:
  enum class Phase { waiting, stimulus, gap, answer, done };

  TrialTimeline(const StudyTiming& timing, Nanos start, int stimuli);

  Nanos onset(int k) const { return start_ + timing_.lead + k * timing_.stimulus_interval; }
  Nanos answer_opens() const { return onset(stimuli_ - 1) + timing_.stimulus; }
  int stimuli() const { return stimuli_; }

  Phase phase(Nanos now) const;
  //! The stimulus shown at `now`, if any (0-based).
  std::optional<int> showing(Nanos now) const;

  //! An answer given at t: its response time, or nothing if the window was not open
  //! (too early, or already answered).
  std::optional<Nanos> answer(Nanos t);
  std::optional<Nanos> response_time() const { return response_; }
  //! When the next trial starts; only once answered.
  std::optional<Nanos> next_start() const;

 private:
  StudyTiming timing_;
  Nanos start_;
  int stimuli_;
  std::optional<Nanos> answered_at_;
  std::optional<Nanos> response_;
};

}  // namespace mallet::study
