#pragma once
// `mallet study`: one participant's session of a protocol. Trials are presented through
// the kiosk's own strike path (study_stimuli.hpp); each answered trial is appended to the
// results CSV and fsync'd before the next begins. Starting again with the same
// participant resumes: the schedule is deterministic, so the trials already in the file
// are skipped and the rest run in their original order.
//
// The trial logic (present → answer → row) is shared by two ways of running it, which
// differ only in their StudyStage (the clock, and where the stimuli go) and AnswerSource:
//   headless: a simulated clock, the HeadlessLoop; answers from a script or the simulated
//             observer (run_study);
//   windowed: the monotonic clock, a real window, the audio device; answers from the
//             participant's keys (study_window.hpp).
#include <filesystem>
#include <algorithm>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/strike/strike_route.hpp"
#include "core/actuator_eq_file.hpp"
#include "core/app_config.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"
#include "core/study/adaptive_schedule.hpp"
#include "core/study/balanced_schedule.hpp"
#include "core/study/results_csv.hpp"
#include "core/study/study_protocol.hpp"

namespace mallet::app {

struct StudyOptions {
  std::filesystem::path protocol;
  std::string participant;
  std::optional<std::filesystem::path> out;      //!< results CSV; default: the protocol's `output`
  std::filesystem::path scene;  //!< empty: the shipped scene of the protocol's kind (percussion, texture)
  std::optional<std::filesystem::path> config;   //!< mallet.toml; built-in defaults if absent
  std::optional<std::filesystem::path> config_dir;  //!< its drop-ins (none: FILE.d)
  std::optional<std::filesystem::path> answers;  //!< answer script; absent: the simulated observer
  std::optional<std::filesystem::path> audio;    //!< WAV of this run's stimuli (both channels)
  std::function<void(int rows_this_run)> after_row;  //!< called after each row is durable
};

struct StudyRunResult {
  std::filesystem::path csv;
  int total = 0;             //!< trials in the participant's schedule (adaptive: at most)
  std::string procedure = "constant";  //!< the protocol's: constant, staircase, quest or quest_plus
  int already_recorded = 0;  //!< found in the CSV at start
  int answered = 0;          //!< in this run
  int correct = 0;           //!< in this run
  bool simulated = false;    //!< the simulated observer answered
  std::string source;        //!< the rows' `source` (AnswerSource::name)
  bool answers_ran_out = false;
  bool stopped = false;      //!< the answer source stopped before the schedule's end (script, Esc)
  bool validation_failed = false;  //!< in a window: Vulkan validation reported a message
  std::vector<std::string> warnings;  //!< FILE:LINE: ... (an incomplete last line ignored)
  std::vector<std::filesystem::path> written;
};

//! Everything checked before a trial runs: the protocol against the scene and settings,
//! the participant's schedule, and the trials already in the CSV.
struct StudyPlan {
  AppConfig config;
  Scene base;
  study::StudyProtocol protocol;
  std::vector<study::ScheduledTrial> schedule;
  std::filesystem::path csv;
  study::ResultsFile existing;
  std::set<int> done;  //!< trial numbers already recorded for this participant
  std::string participant;
  //! The schedule's trials (constant), or the most an adaptive protocol's tracks may take.
  int total_trials = 0;
  //! Nothing left to run: every trial recorded, or every adaptive track done.
  bool finished = false;
  //! A visitor's session (visitor_study.hpp): at most this many trials (0: all), and its
  //! `session` column (empty: the run's start, UTC).
  int max_trials = 0;
  std::string session;
  //! The rows' planned_trials: total_trials, or max_trials when it is fewer.
  int planned_trials() const { return max_trials > 0 ? std::min(max_trials, total_trials) : total_trials; }
  int stimuli_per_trial() const;
};

//! An adaptive protocol's tracks after this participant's recorded rows, replayed in trial
//! order (checked by plan_study: each row is the trial the tracks gave).
study::AdaptiveSchedule replay_adaptive(const StudyPlan& plan);

//! Bad protocol, scene, config or CSV → FileError (exit 2).
StudyPlan plan_study(const StudyOptions& options);
//! The same checks and plan from what is already loaded (the kiosk's visitor study).
StudyPlan plan_session(AppConfig config, Scene base, study::StudyProtocol protocol, const std::string& participant,
                       const std::filesystem::path& csv);

//! What a crossing of a texture_slope trial presented, measured on the strike route's own
//! output: the largest distance between the drawn cursor and the hand (the Speed
//! technique's visible effect, metres) and the largest actuator sample (the stripes).
struct Exploration {
  double cursor_offset_peak_m = 0;
  double actuator_peak = 0;
};

//! One crossing's hand samples (world metres, any clock) through `trial_scene`'s own route
//! and engine, offline: what it presented.
Exploration measure_crossing(const Scene& trial_scene, const AppConfig& config, const std::vector<PointerSample>& hand);

//! Where a trial is presented, on its own clock (int64 ns).
class StudyStage {
 public:
  virtual ~StudyStage() = default;
  virtual Nanos now() = 0;
  //! Lets time run up to t (headless: renders up to it; windowed: draws frames until
  //! then). False: the participant asked to stop.
  virtual bool wait_until(Nanos t) = 0;
  //! A stimulus tap (impact.t_ns = now()): the actuator, the sound and the bounce, through
  //! the strike route, which says when they are heard and shown.
  virtual Strike present(const Impact& impact) = 0;
  //! Eq. 1's visual displacement of the latest tap at t (metres).
  virtual double visual_offset_m(Nanos t) const = 0;
  //! The largest |actuator sample| of the stimuli since the last call.
  virtual double take_actuator_peak() = 0;
  //! The question of the trial about to run (windowed: shown on the screen).
  virtual void trial_starts(const study::ScheduledTrial&) {}
  //! A participant's hand (sphere centre, world metres) at t >= now(), through the same
  //! strike route as the stimuli: the strike it made, if any (answers by striking).
  virtual std::optional<Strike> hand(Nanos t, Vec2 hand) = 0;
  //! texture_slope: the participant crosses `trial_scene`'s disc from now until `until`
  //! (headless: a straight crossing through its centre); what it presented.
  virtual Exploration explore(const Scene& trial_scene, Nanos until) = 0;
  //! The actuator calibration whose inverse the stage's engine applies (audio_setup.hpp), for
  //! the results' actuator_eq_hash and actuator_eq_utc; none when it applies none.
  virtual std::optional<ActuatorEq> actuator_eq() const = 0;
};

//! An answer, given at `at` on the stage's clock.
struct TrialAnswer {
  std::string answer;
  Nanos at = 0;
};

class AnswerSource {
 public:
  virtual ~AnswerSource() = default;
  //! False: no answer can come any more (a script ran out); the trial is not presented.
  virtual bool has_more() const { return true; }
  //! The answer to `trial`, whose answer window opened at `opens` (the end of the last
  //! stimulus); nothing: stop here (the participant quit, or no answer is left).
  virtual std::optional<TrialAnswer> answer(const study::ScheduledTrial& trial, Nanos opens) = 0;
  //! The rows' `source` column: "file", "simulated", "keys", "strike".
  virtual std::string name() const = 0;
};

//! One trial on `stage` from `start`: its stimuli, the answer, the row (not yet written).
//! Nothing when the stage or the source stopped. `next_start`: when the next trial starts.
std::optional<study::ResultRow> run_trial(const StudyPlan& plan, const Scene& study_scene,
                                          const study::ScheduledTrial& trial, StudyStage& stage,
                                          AnswerSource& answers, Nanos start, const std::string& session,
                                          Nanos& next_start);

//! What a run that runs no trial reports (every trial already recorded).
StudyRunResult nothing_run(const StudyPlan& plan);

//! The remaining trials of the plan through `stage` and `answers`, each row durable
//! before the next trial. `study_scene` = make_study_scene(plan.base, plan.protocol)
//! (in a window: study_scene_for, laid out for its shape).
StudyRunResult run_session(const StudyPlan& plan, const Scene& study_scene, StudyStage& stage,
                           AnswerSource& answers, const std::function<void(int)>& after_row = {});

//! The keys a participant answers with: the first letters of the protocol's answers when
//! they are distinct ("1"/"2"; R rubber, W wood, A aluminium), else the digits 1..9.
struct AnswerKey {
  char key;  //!< upper-case letter or digit
  std::string answer;
};
std::vector<AnswerKey> answer_keys(const study::StudyProtocol& protocol);
//! "Which tap felt harder? Press 1 or 2" / "Which material? R rubber, W wood, A aluminium";
//! with response = "strike": "... Strike 1 or 2" / "Which material? Strike its bar".
std::string answer_prompt(const study::StudyProtocol& protocol);

//! Headless: bad protocol, scene, config, answers or CSV → FileError (exit 2); a failure to
//! write → std::runtime_error (exit 1).
StudyRunResult run_study(const StudyOptions& options);

}  // namespace mallet::app
