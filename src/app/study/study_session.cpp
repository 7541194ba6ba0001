#include "app/study/study_session.hpp"

#include <algorithm>
#include <cctype>
#include <utility>
#include <cmath>
#include <ctime>
#include <memory>
#include <set>

#include "app/study/study_headless.hpp"
#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "app/study/study_stimuli.hpp"
#include "core/actuator_signal.hpp"
#include "core/config/instruments_config.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/named.hpp"
#include "core/study/answer_script.hpp"
#include "core/study/balanced_schedule.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/study/results_csv.hpp"
#include "core/study/simulated_observer.hpp"
#include "core/study/trial_timeline.hpp"
#include "core/visitor_language.hpp"

namespace mallet::app {

namespace fs = std::filesystem;
using namespace mallet::study;

namespace {

constexpr Nanos kVisualProbe = 1'000'000;  // the bounce is sampled every 1 ms for its peak

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

//! The participant's rows already in the file, checked against the schedule: trial N
//! must be the trial N this protocol gives this participant.
std::set<int> recorded_trials(const ResultsFile& file, const fs::path& csv, const StudyProtocol& protocol,
                              const std::string& participant, const std::vector<ScheduledTrial>& schedule) {
  std::set<int> done;
  for (std::size_t i = 0; i < file.rows.size(); ++i) {
    const ResultRow& r = file.rows[i];
    if (r.participant != participant) continue;
    const std::uint32_t line = file.lines[i];
    if (r.trial > static_cast<int>(schedule.size()))
      throw FileError(csv.string(), line, 0,
                      "trial " + std::to_string(r.trial) + " of " + participant + ", but " + protocol.file +
                          " gives only " + std::to_string(schedule.size()) +
                          " trials (another protocol? use a new --out)");
    const ScheduledTrial& t = schedule[static_cast<std::size_t>(r.trial - 1)];
    const std::string condition(condition_name(t.condition));
    const std::string stimuli = stimuli_text(protocol, t);
    if (r.condition != condition || r.stimuli != stimuli || (!r.protocol.empty() && r.protocol != protocol.name))
      throw FileError(csv.string(), line, 0,
                      "trial " + std::to_string(r.trial) + " of " + participant + " is " + r.condition + " " +
                          r.stimuli + " here, but " + protocol.file + " schedules " + condition + " " + stimuli +
                          " (protocol changed? use a new --out)");
    if (!done.insert(r.trial).second)
      throw FileError(csv.string(), line, 0,
                      "trial " + std::to_string(r.trial) + " of " + participant + " is recorded twice");
  }
  return done;
}

//! An adaptive protocol's rows of this participant, replayed into its tracks: each must be
//! the trial the tracks give next, in trial order from 1.
AdaptiveSchedule replay_rows(const ResultsFile& file, const fs::path& csv, const StudyProtocol& protocol,
                             const std::string& participant) {
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < file.rows.size(); ++i)
    if (file.rows[i].participant == participant) mine.push_back(i);
  std::stable_sort(mine.begin(), mine.end(),
                   [&](std::size_t a, std::size_t b) { return file.rows[a].trial < file.rows[b].trial; });
  AdaptiveSchedule schedule(protocol, participant);
  for (std::size_t i : mine) {
    const ResultRow& r = file.rows[i];
    const std::uint32_t line = file.lines[i];
    const std::string trial_text = "trial " + std::to_string(r.trial) + " of " + participant;
    if (r.trial != schedule.trials() + 1)
      throw FileError(csv.string(), line, 0,
                      trial_text + (r.trial <= schedule.trials() ? " is recorded twice"
                                                                 : " comes after a missing trial " +
                                                                       std::to_string(schedule.trials() + 1)));
    const std::optional<ScheduledTrial> expected = schedule.next();
    if (!expected)
      throw FileError(csv.string(), line, 0,
                      trial_text + ", but " + protocol.file + "'s tracks were done before it (another protocol? "
                                   "use a new --out)");
    const std::string condition(condition_name(expected->condition));
    const std::string stimuli = stimuli_text(protocol, *expected);
    if (r.condition != condition || r.stimuli != stimuli || (!r.protocol.empty() && r.protocol != protocol.name))
      throw FileError(csv.string(), line, 0,
                      trial_text + " is " + r.condition + " " + r.stimuli + " here, but " + protocol.file +
                          "'s tracks give " + condition + " " + stimuli + " (protocol changed? use a new --out)");
    schedule.record(*expected, r.correct);
  }
  return schedule;
}

}  // namespace

AdaptiveSchedule replay_adaptive(const StudyPlan& plan) {
  return replay_rows(plan.existing, plan.csv, plan.protocol, plan.participant);
}

int StudyPlan::stimuli_per_trial() const { return protocol.paired() ? 2 : 1; }

Exploration measure_crossing(const Scene& scene, const AppConfig& config, const std::vector<PointerSample>& hand) {
  Exploration out;
  if (hand.empty()) return out;
  HeadlessLoop loop(scene, config, HeadlessLoop::kNoAttract);
  const int actuator = config.audio.routing.actuator;
  const auto channels = static_cast<std::size_t>(loop.channels());
  loop.on_audio = [&](std::span<const float> block) {
    for (std::size_t i = static_cast<std::size_t>(actuator); i < block.size(); i += channels)
      out.actuator_peak = std::max(out.actuator_peak, static_cast<double>(std::fabs(block[i])));
  };
  const Nanos t0 = hand.front().t_ns;  // on the loop's own clock from 0
  for (const PointerSample& p : hand) {
    loop.visitor(p.t_ns - t0, {p.x, p.y});
    const Vec2 c = loop.strike_loop().view().shown;
    out.cursor_offset_peak_m = std::max(out.cursor_offset_peak_m, std::hypot(c.x - p.x, c.y - p.y));
  }
  loop.drain_audio(hand.back().t_ns - t0 + 100'000'000);  // the stripes' fade after the last motion
  return out;
}

StudyPlan plan_session(AppConfig config, Scene base, StudyProtocol protocol, const std::string& participant,
                       const fs::path& csv) {
  StudyPlan p;
  p.participant = participant;
  p.config = std::move(config);
  p.base = std::move(base);
  p.protocol = std::move(protocol);
  if (p.protocol.texture() != (p.base.kind == SceneKind::texture))
    throw FileError(p.protocol.file, 0, 0,
                    p.protocol.texture() ? "task texture_slope needs a texture scene (--scene config/scenes/texture.toml), not " + p.base.file
                                         : std::string("a percussion task needs a percussion scene, not ") + p.base.file);
  const int rate = p.config.audio.sample_rate_hz;
  for (const Stimulus& s : p.protocol.stimuli)
    if (auto problem = s.relief ? std::nullopt : actuator_band_problem(s.material, rate))
      throw FileError(p.protocol.file, 0, 0, "stimulus " + s.name + ": " + *problem);
  if (p.protocol.response == StudyResponse::strike && !p.protocol.answer_strike.voice.empty()) {
    const std::vector<ModalPreset> voices = config::load_instruments(p.base.instruments_file);
    const std::string& voice = p.protocol.answer_strike.voice;
    if (!find_named(voices, voice))
      throw FileError(p.protocol.answer_strike.voice_at, "answer_strike.sound: no voice \"" + voice + "\" in " +
                                                          p.base.instruments_file +
                                                          " (known: " + names_of(voices) + ", none)");
  }
  p.schedule = balanced_schedule(p.protocol, participant);
  p.csv = csv;
  p.existing = read_results(p.csv);
  if (p.existing.has_header && results_columns(p.existing.header) == 0)
    throw FileError(p.csv.string(), 1, 0,
                    "its columns are not the ones this version writes; use a new --out (expected " +
                        std::string(kResultsHeader) + ")");
  if (p.protocol.procedure == StudyProcedure::constant) {
    p.done = recorded_trials(p.existing, p.csv, p.protocol, participant, p.schedule);
    p.total_trials = static_cast<int>(p.schedule.size());
    p.finished = p.done.size() == p.schedule.size();
  } else {
    const AdaptiveSchedule replayed = replay_rows(p.existing, p.csv, p.protocol, participant);
    for (int n = 1; n <= replayed.trials(); ++n) p.done.insert(n);
    p.total_trials = replayed.max_trials();
    p.finished = !replayed.next();
  }
  return p;
}

StudyPlan plan_study(const StudyOptions& o) {
  // --- everything that can be wrong with the input is found before a trial runs
  if (!is_plain_name(o.participant))
    throw FileError("--participant", 0, 0,
                    "\"" + o.participant + "\" must be 1-64 letters, digits, '_', '-' or '.'");
  AppConfig config = command_settings(o.config, o.config_dir, "study");
  Scene base = config::load_scene(o.scene.empty() ? default_scene() : o.scene);
  StudyProtocol protocol = load_study_protocol(o.protocol, base.materials, base.targets.size());
  if (o.scene.empty() && protocol.texture()) {  // no --scene: the shipped scene of the task's kind
    base = config::load_scene(config_dir() / "scenes" / "texture.toml");
    protocol = load_study_protocol(o.protocol, base.materials, base.targets.size());
  }
  const fs::path csv = o.out ? *o.out : fs::path(protocol.output);
  return plan_session(std::move(config), std::move(base), std::move(protocol), o.participant, csv);
}

std::optional<ResultRow> run_trial(const StudyPlan& plan, const Scene& scene, const ScheduledTrial& trial,
                                   StudyStage& stage, AnswerSource& answers, Nanos start,
                                   const std::string& session, Nanos& next_start) {
  const StudyProtocol& protocol = plan.protocol;
  const int stimuli = plan.stimuli_per_trial();
  TrialTimeline timeline(protocol.timing, start, stimuli);
  stage.trial_starts(trial);
  if (!stage.wait_until(timeline.onset(0))) return std::nullopt;
  stage.take_actuator_peak();
  double visual_peak = 0, crossing_peak = 0;
  // The cues' onsets from the strike route, relative to each tap's contact: the latest of
  // the trial's taps (a trial is as late as its latest cue).
  Nanos actuator_onset = 0, picture_onset = 0;
  const std::vector<int> shown = shown_stimuli(protocol, trial);
  bool tapped = false;
  for (int k = 0; k < stimuli; ++k) {
    if (protocol.texture()) {  // a crossing of the disc, for as long as a stimulus lasts
      const Stimulus& s = protocol.stimuli[static_cast<std::size_t>(shown[static_cast<std::size_t>(k)])];
      const Exploration e = stage.explore(texture_trial_scene(scene, s, trial.condition),
                                          timeline.onset(k) + protocol.timing.stimulus);
      visual_peak = std::max(visual_peak, e.cursor_offset_peak_m);
      crossing_peak = std::max(crossing_peak, e.actuator_peak);
      if (!stage.wait_until(k + 1 < stimuli ? timeline.onset(k + 1) : timeline.answer_opens())) return std::nullopt;
      continue;
    }
    tapped = true;
    const Strike strike = stage.present(
        stimulus_impact(scene, protocol, shown[static_cast<std::size_t>(k)], trial.condition, timeline.onset(k)));
    actuator_onset = std::max(actuator_onset, strike.heard_ns - strike.impact.t_ns);
    picture_onset = std::max(picture_onset, strike.shown_ns - strike.impact.t_ns);
    const Nanos end = timeline.onset(k) + protocol.timing.stimulus;
    for (Nanos probe = timeline.onset(k); probe < end; probe += kVisualProbe)
      visual_peak = std::max(visual_peak, std::fabs(stage.visual_offset_m(probe)));
    if (!stage.wait_until(k + 1 < stimuli ? timeline.onset(k + 1) : timeline.answer_opens())) return std::nullopt;
  }
  const double actuator_peak = std::max(stage.take_actuator_peak(), crossing_peak);
  const std::optional<TrialAnswer> given = answers.answer(trial, timeline.answer_opens());
  if (!given) return std::nullopt;
  // An answer from before the window opened cannot come from a source (it ignores those);
  // clamp so that the timeline takes it whatever the clock did.
  const Nanos response = *timeline.answer(std::max(given->at, timeline.answer_opens()));
  if (!stage.wait_until(timeline.answer_opens() + response)) {
    // The answer was given: it is kept even if the participant quits right after.
  }

  ResultRow row;
  row.participant = plan.participant;
  row.trial = trial.number;
  row.condition = std::string(condition_name(trial.condition));
  row.stimuli = stimuli_text(protocol, trial);
  row.answer = given->answer;
  row.correct = given->answer == correct_answer(protocol, trial);
  row.response_time_ms = static_cast<double>(response) / 1e6;
  row.protocol = protocol.name;
  row.task = std::string(task_name(protocol.task));
  row.difference_pct = difference_pct(protocol, trial);
  row.source = answers.name();
  row.session = session;
  row.visual_peak_m = visual_peak;
  row.actuator_peak = actuator_peak;
  row.language = visitor_language();  // the language the trial's words were shown in
  if (tapped) {  // a crossing is no strike: no onsets
    row.actuator_onset_ms = static_cast<double>(actuator_onset) / 1e6;
    row.picture_onset_ms = static_cast<double>(picture_onset) / 1e6;
  }
  next_start = *timeline.next_start();
  return row;
}

StudyRunResult nothing_run(const StudyPlan& plan) {
  StudyRunResult result;
  result.csv = plan.csv;
  result.total = plan.total_trials;
  result.procedure = std::string(procedure_name(plan.protocol.procedure));
  result.warnings = plan.existing.warnings;
  result.already_recorded = static_cast<int>(plan.done.size());
  return result;
}

StudyRunResult run_session(const StudyPlan& plan, const Scene& scene, StudyStage& stage, AnswerSource& answers,
                           const std::function<void(int)>& after_row) {
  StudyRunResult result = nothing_run(plan);
  result.source = answers.name();
  if (plan.finished) return result;
  // The trials still to run: the schedule's not yet recorded, or what the adaptive tracks
  // give, one at a time, after replaying the recorded rows.
  std::optional<AdaptiveSchedule> adaptive;
  if (plan.protocol.procedure != StudyProcedure::constant) adaptive.emplace(replay_adaptive(plan));
  std::size_t next_index = 0;
  auto next_trial = [&]() -> std::optional<ScheduledTrial> {
    if (adaptive) return adaptive->next();
    while (next_index < plan.schedule.size() && plan.done.contains(plan.schedule[next_index].number)) ++next_index;
    if (next_index == plan.schedule.size()) return std::nullopt;
    return plan.schedule[next_index++];
  };
  ResultsWriter writer(plan.csv, plan.existing);
  const std::string session = plan.session.empty() ? utc_now() : plan.session;
  const std::optional<ActuatorEq> eq = stage.actuator_eq();  // what the stage's engine applies
  Nanos t = stage.now();
  const std::string procedure(procedure_name(plan.protocol.procedure));
  while (const std::optional<ScheduledTrial> next_one = next_trial()) {
    const ScheduledTrial& trial = *next_one;
    if (plan.max_trials > 0 && result.already_recorded + result.answered >= plan.max_trials) break;
    if (!answers.has_more()) {
      result.stopped = true;
      break;
    }
    Nanos next = t;
    std::optional<ResultRow> row = run_trial(plan, scene, trial, stage, answers, t, session, next);
    if (!row) {
      result.stopped = true;
      break;
    }
    row->procedure = procedure;
    row->planned_trials = plan.planned_trials();
    if (eq) {
      row->actuator_eq_hash = eq->hash();
      row->actuator_eq_utc = eq->created_utc;
    }
    if (adaptive) {  // the track's state after this answer
      adaptive->record(trial, row->correct);
      const TrackState s = adaptive->state(trial.condition);
      row->track_trial = s.trials;
      row->reversals = s.reversals;
      if (s.estimate_pct) row->estimate_pct = *s.estimate_pct;
      if (s.estimate_sd_pct) row->estimate_sd_pct = *s.estimate_sd_pct;
      if (s.estimate_mode_pct) row->estimate_mode_pct = *s.estimate_mode_pct;
    }
    writer.append(*row);
    ++result.answered;
    result.correct += row->correct ? 1 : 0;
    if (after_row) after_row(result.answered);
    t = next;
  }
  result.written.push_back(plan.csv);
  return result;
}

std::vector<AnswerKey> answer_keys(const StudyProtocol& protocol) {
  const std::vector<std::string> choices = protocol.answer_choices();
  std::vector<AnswerKey> keys;
  std::set<char> used;
  bool letters = true;
  for (const std::string& c : choices) {
    const char k = c.empty() ? '\0' : static_cast<char>(std::toupper(static_cast<unsigned char>(c[0])));
    if (!std::isalnum(static_cast<unsigned char>(k)) || !used.insert(k).second) letters = false;
  }
  for (std::size_t i = 0; i < choices.size(); ++i) {
    const char k = letters ? static_cast<char>(std::toupper(static_cast<unsigned char>(choices[i][0])))
                           : static_cast<char>('1' + i);
    if (!letters && i >= 9) break;  // more than 9 materials cannot be answered by a key
    keys.push_back({k, choices[i]});
  }
  return keys;
}

std::string answer_prompt(const StudyProtocol& protocol) {
  const bool strike = protocol.response == StudyResponse::strike;
  if (protocol.texture())
    return protocol.paired() ? tr("Which was steeper? Press 1 or 2") : tr("A bump or a hole? Press B or H");
  if (protocol.task == StudyTask::two_afc_harder)
    return strike ? tr("Which tap felt harder? Strike 1 or 2") : tr("Which tap felt harder? Press 1 or 2");
  if (strike) return tr("Which material? Strike its bar");
  const std::vector<AnswerKey> keys = answer_keys(protocol);
  std::string text = tr("Which material?");
  for (std::size_t i = 0; i < keys.size(); ++i)
    text += std::string(i ? ", " : " ") + keys[i].key + " " + keys[i].answer;
  return text;
}


StudyRunResult run_study(const StudyOptions& o) {
  const StudyPlan plan = plan_study(o);
  std::vector<ObserverAnswer> script;
  if (o.answers) script = read_answer_script(*o.answers, plan.protocol.answer_choices());
  if (plan.finished) {  // nothing left: the file is not touched
    StudyRunResult r = nothing_run(plan);
    r.simulated = !o.answers;
    return r;
  }
  const Scene scene = make_study_scene(plan.base, plan.protocol);
  HeadlessStage stage(scene, plan, o.audio);
  ScriptedAnswers scripted(plan, std::move(script), !o.answers);
  StrikeAnswers struck(scripted, stage, scene, plan.protocol);
  AnswerSource& answers = plan.protocol.response == StudyResponse::strike ? static_cast<AnswerSource&>(struck) : scripted;
  StudyRunResult result = run_session(plan, scene, stage, answers, o.after_row);
  result.simulated = !o.answers;
  result.answers_ran_out = o.answers && result.stopped;
  stage.finish();
  if (o.audio) result.written.push_back(*o.audio);
  return result;
}

}  // namespace mallet::app
