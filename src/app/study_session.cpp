#include "app/study_session.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <memory>
#include <set>

#include "app/headless_loop.hpp"
#include "app/study_stimuli.hpp"
#include "audio/wav_file.hpp"
#include "core/actuator_signal.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/study/answer_script.hpp"
#include "core/study/balanced_schedule.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/study/results_csv.hpp"
#include "core/study/simulated_observer.hpp"
#include "core/study/trial_timeline.hpp"

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

}  // namespace

StudyRunResult run_study(const StudyOptions& o) {
  // --- everything that can be wrong with the input is found before a trial runs
  if (!is_plain_name(o.participant))
    throw FileError("--participant", 0, 0,
                    "\"" + o.participant + "\" must be 1-64 letters, digits, '_', '-' or '.'");
  const AppConfig config = o.config ? config::load_app_config(*o.config) : AppConfig{};
  const Scene base = config::load_scene(o.scene);
  const StudyProtocol protocol = load_study_protocol(o.protocol, base.materials, base.targets.size());
  const int rate = config.audio.sample_rate_hz;
  for (const Stimulus& s : protocol.stimuli)
    if (auto problem = actuator_band_problem(s.material, rate))
      throw FileError(protocol.file, 0, 0, "stimulus " + s.name + ": " + *problem);
  const std::vector<ScheduledTrial> schedule = balanced_schedule(protocol, o.participant);
  std::vector<ObserverAnswer> script;
  if (o.answers) script = read_answer_script(*o.answers, protocol.answer_choices());
  const SimulatedObserver observer(protocol, o.participant);

  StudyRunResult result;
  result.csv = o.out ? *o.out : fs::path(protocol.output);
  result.total = static_cast<int>(schedule.size());
  result.simulated = !o.answers;
  const ResultsFile existing = read_results(result.csv);
  if (existing.has_header && existing.header != kResultsHeader)
    throw FileError(result.csv.string(), 1, 0,
                    "its columns are not the ones this version writes; use a new --out (expected " +
                        std::string(kResultsHeader) + ")");
  result.warnings = existing.warnings;
  const std::set<int> done = recorded_trials(existing, result.csv, protocol, o.participant, schedule);
  result.already_recorded = static_cast<int>(done.size());
  if (result.already_recorded == result.total) return result;

  // --- the session
  const Scene scene = make_study_scene(base, protocol);
  HeadlessLoop loop(scene, config, HeadlessLoop::kNoAttract, protocol.sound);
  std::unique_ptr<audio::WavWriter> wav;
  if (o.audio) wav = std::make_unique<audio::WavWriter>(*o.audio, loop.channels(), rate);
  const int channels = loop.channels();
  const int actuator_channel = config.audio.routing.actuator;
  double actuator_peak = 0;
  loop.on_audio = [&](std::span<const float> block) {
    if (wav) wav->write(block);
    for (std::size_t i = static_cast<std::size_t>(actuator_channel); i < block.size(); i += static_cast<std::size_t>(channels))
      actuator_peak = std::max(actuator_peak, static_cast<double>(std::fabs(block[i])));
  };
  ResultsWriter writer(result.csv, existing);
  const std::string session = utc_now();
  const int stimuli_per_trial = protocol.task == StudyTask::two_afc_harder ? 2 : 1;

  Nanos t = 0;
  std::size_t next_answer = 0;
  for (const ScheduledTrial& trial : schedule) {
    if (done.contains(trial.number)) continue;
    if (o.answers && next_answer == script.size()) {
      result.answers_ran_out = true;
      break;
    }
    TrialTimeline timeline(protocol.timing, t, stimuli_per_trial);
    loop.advance(timeline.onset(0));
    actuator_peak = 0;
    double visual_peak = 0;
    const std::vector<int> shown = shown_stimuli(protocol, trial);
    for (int k = 0; k < stimuli_per_trial; ++k) {
      loop.present(stimulus_impact(scene, protocol, shown[static_cast<std::size_t>(k)], trial.condition, timeline.onset(k)));
      const Nanos end = timeline.onset(k) + protocol.timing.stimulus;
      for (Nanos probe = timeline.onset(k); probe < end; probe += kVisualProbe)
        visual_peak = std::max(visual_peak, std::fabs(loop.visual_offset_m(probe)));
      loop.advance(k + 1 < stimuli_per_trial ? timeline.onset(k + 1) : timeline.answer_opens());
    }
    const ObserverAnswer given = o.answers ? script[next_answer++] : observer.respond(trial);
    const Nanos response = *timeline.answer(timeline.answer_opens() + given.response_time);
    loop.advance(timeline.answer_opens() + response);

    ResultRow row;
    row.participant = o.participant;
    row.trial = trial.number;
    row.condition = std::string(condition_name(trial.condition));
    row.stimuli = stimuli_text(protocol, trial);
    row.answer = given.answer;
    row.correct = given.answer == correct_answer(protocol, trial);
    row.response_time_ms = static_cast<double>(response) / 1e6;
    row.protocol = protocol.name;
    row.task = std::string(task_name(protocol.task));
    row.difference_pct = difference_pct(protocol, trial);
    row.source = o.answers ? "file" : "simulated";
    row.session = session;
    row.visual_peak_m = visual_peak;
    row.actuator_peak = actuator_peak;
    writer.append(row);
    ++result.answered;
    result.correct += row.correct ? 1 : 0;
    if (o.after_row) o.after_row(result.answered);
    t = *timeline.next_start();
  }
  loop.drain_audio(t + kNanosPerSecond);
  if (wav) {
    wav->close();
    result.written.push_back(*o.audio);
  }
  result.written.insert(result.written.begin(), result.csv);
  return result;
}

}  // namespace mallet::app
