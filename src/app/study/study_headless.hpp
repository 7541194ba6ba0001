#pragma once
// The study on a simulated clock, without a window (`mallet study --headless`, the visitor
// study's simulated visitors, the tests): the stage is the kiosk's HeadlessLoop, and the
// answers are given in advance (--answers) or by the simulated observer, by keys or, with
// response = "strike", struck on the answer bars through the same strike route as the
// stimuli.
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "app/strike/headless_loop.hpp"
#include "app/study/study_session.hpp"
#include "app/study/study_stimuli.hpp"
#include "audio/wav_file.hpp"
#include "core/study/simulated_observer.hpp"

namespace mallet::app {

//! The simulated clock: the kiosk's loop without a window; the stimuli optionally written
//! to a WAV (both channels).
class HeadlessStage final : public StudyStage {
 public:
  HeadlessStage(const Scene& study_scene, const StudyPlan& plan, const std::optional<std::filesystem::path>& wav);
  Nanos now() override { return loop_.now(); }
  bool wait_until(Nanos t) override;
  Strike present(const Impact& impact) override { return loop_.present(impact); }
  double visual_offset_m(Nanos t) const override { return loop_.visual_offset_m(t); }
  double take_actuator_peak() override;
  std::optional<Strike> hand(Nanos t, Vec2 hand) override { return loop_.visitor(t, hand); }
  //! A straight crossing through the disc's centre, left to right, from 0.4 R outside it on
  //! each side, at constant speed over the time given (sampled at 1 kHz).
  Exploration explore(const Scene& trial_scene, Nanos until) override;
  std::optional<ActuatorEq> actuator_eq() const override { return loop_.actuator_eq(); }
  //! The audio's last second rendered, and the WAV closed.
  void finish();

 private:
  HeadlessLoop loop_;
  const AppConfig& config_;
  int actuator_channel_;
  std::unique_ptr<audio::WavWriter> wav_;
  double peak_ = 0;
};

//! Answers given in advance (--answers) or, without a script, by the simulated observer.
class ScriptedAnswers final : public AnswerSource {
 public:
  ScriptedAnswers(const StudyPlan& plan, std::vector<study::ObserverAnswer> script, bool simulated);
  bool has_more() const override { return simulated_ || next_ < script_.size(); }
  std::optional<TrialAnswer> answer(const study::ScheduledTrial& trial, Nanos opens) override;
  std::string name() const override { return simulated_ ? "simulated" : "file"; }

 private:
  study::SimulatedObserver observer_;
  std::vector<study::ObserverAnswer> script_;
  bool simulated_;
  std::size_t next_ = 0;
};

//! A hand strikes answer bar `bars[index]` on ghost_player's stroke (sampled at 1 kHz, at
//! `speed`) through the stage's strike route, its contact due at `at` (later when a stroke
//! from hover height started now cannot land so soon). The answer is the bar the route says
//! was struck at or after `opens`, at the contact it found; std::logic_error if the stroke
//! struck none.
TrialAnswer strike_answer_bar(StudyStage& stage, const Scene& study_scene, const std::vector<AnswerBar>& bars,
                              std::size_t index, Nanos at, Nanos opens, double speed);

//! Answers by striking (response = "strike"): `choices` (a script or the simulated
//! observer) says which answer and when its strike should land; strike_answer_bar strikes it.
class StrikeAnswers final : public AnswerSource {
 public:
  StrikeAnswers(AnswerSource& choices, StudyStage& stage, const Scene& study_scene,
                const study::StudyProtocol& protocol);
  bool has_more() const override { return choices_.has_more(); }
  std::optional<TrialAnswer> answer(const study::ScheduledTrial& trial, Nanos opens) override;
  std::string name() const override { return "strike"; }

 private:
  AnswerSource& choices_;
  StudyStage& stage_;
  const Scene& scene_;
  std::vector<AnswerBar> bars_;
  double speed_;
};

}  // namespace mallet::app
