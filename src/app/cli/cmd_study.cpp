#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/common/settings_source.hpp"
#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/study/study_report.hpp"
#include "app/study/study_session.hpp"
#include "app/study/study_window.hpp"
#include "app/study/visitor_study.hpp"
#include "core/file_error.hpp"
#include "core/study/results_csv.hpp"
#include "core/study/study_summary.hpp"
#include "core/study/visitor_offer.hpp"
#include "render/window_target.hpp"

namespace mallet::app {

namespace {

struct SummaryFlags {
  std::vector<std::string> results;
  std::string participant;
  int resamples = study::kDefaultResamples;
  std::uint64_t seed = 1;
  std::filesystem::path plots, report, table, json;
  std::string shape = "logistic";
  std::string lapse = "0";
  double criterion = 0.75;
};

//! `--lapse fit|0|VALUE` into the fit's options; "" when it reads, else what is wrong.
std::string read_lapse(const std::string& v, study::FitOptions& fit) {
  if (v == "fit") {
    fit.fit_lapse = true;
    return {};
  }
  char* end = nullptr;
  const double lapse = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0' || !(lapse >= 0 && lapse < 0.5))
    return "\"fit\", or a fixed lapse rate from 0 to below 0.5, not \"" + v + "\"";
  fit.fit_lapse = false;
  fit.lapse = lapse;
  return {};
}

void add_summary(CLI::App& study) {
  auto o = std::make_shared<SummaryFlags>();
  CLI::App* cmd = study.add_subcommand("summary", "Per-condition accuracy and a psychometric fit of results CSVs");
  cmd->footer(R"(Reads every results file named, and every *.csv in each folder named (in name order), as
one set of rows. Prints, per condition: trials, correct answers, accuracy and mean response
time; then, for 2AFC rows (those with a difference_pct), the maximum-likelihood fit of
  P(correct) = 0.5 + 0.5/(1 + exp(-slope*(x - threshold)))
with x the pair's difference in Eq. 1's B (%): threshold = the 75%-correct difference,
pooled over the participants; then, with more than one participant, each one's fit (not the
visitor micro-study's sessions, visitor-*: they are pooled only, and counted as completed or
abandoned).
Fewer than 3 distinct differences in a condition: "not enough levels", no fit.
Each fit has 95% confidence intervals for its threshold and slope (threshold_95ci,
slope_95ci): the parametric bootstrap, --bootstrap resamples drawn from the fitted curve and
fitted again, bias-corrected percentiles; seeded by --seed, the participant and the
condition, so the same data gives the same intervals.
--plots DIR: psychometric.png (pooled curves, points sized by trials), thresholds.png (each
participant's threshold and interval), response_times.png; each with its .dat and .gp
(gnuplot-nox draws them; without it the data is still written).
--shape logistic|weibull|normal|gumbel: the psychometric function's shape (default logistic);
--criterion C: the threshold is the difference answered correctly C of the time without lapses
(default 0.75, from above 0.5 to below 1); --lapse fit|0|VALUE: the lapse rate fitted within
[0, 0.06] (Wichmann & Hill), or fixed (default 0). A maximum on the search's edge is not an
estimate: "threshold below/above the tested range" and "no rise in accuracy" print "-" with
the reason; "a step" prints the threshold and "slope at least X" (the likelihood-ratio 95 %
limit). An interval that reaches the search's edge is one-sided ("<= 13.37"); a threshold's is
never below 0. Below the fits, the goodness of fit: the deviance, its p-value from the
bootstrap, and each level's deviance residual; with several participants, the group's mean ±
SE and median of their own thresholds.
--table FILE.csv: one row per fit, pooled and per participant (columns: condition,
participant, shape, criterion, lapse_mode, levels, trials, threshold_pct, threshold_lo,
threshold_hi, slope, slope_lo, slope_hi, slope_at_least, lapse, lapse_lo, lapse_hi,
log_likelihood, deviance, deviance_p, resamples, flags, note; an empty cell: no such number).
--json FILE.json: the same fits, and the group's, as JSON.
--report FILE.md: a short markdown report of all of it, embedding the plots.
A file or folder that is missing, or a malformed row: exit 2 with FILE:LINE: problem.)");
  cmd->add_option("--results", o->results, "Results CSVs written by `mallet study`, or folders of them")
      ->required()
      ->expected(1, -1);
  cmd->add_option("--participant", o->participant, "Only this participant's rows (default: all)");
  cmd->add_option("--bootstrap", o->resamples, "Bootstrap resamples per fit for its 95% intervals (0: none)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& v) {
            const long n = std::strtol(v.c_str(), nullptr, 10);
            return n == 0 || (n >= 20 && n <= 100000) ? std::string() : "0, or 20 to 100000 resamples";
          },
          "0 or 20..100000"));
  cmd->add_option("--seed", o->seed, "Seed of the bootstrap's draws")->capture_default_str();
  cmd->add_option("--shape", o->shape, "Psychometric function: logistic, weibull, normal or gumbel")
      ->capture_default_str()
      ->check(CLI::IsMember({"logistic", "weibull", "normal", "gumbel"}));
  cmd->add_option("--lapse", o->lapse, "Lapse rate: fit (within [0, 0.06]), or a fixed value from 0 to below 0.5")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& v) {
            study::FitOptions ignored;
            return read_lapse(v, ignored);
          },
          "fit|0|VALUE"));
  cmd->add_option("--criterion", o->criterion, "The threshold's proportion correct (without lapses)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& v) {
            const double c = std::strtod(v.c_str(), nullptr);
            return c > 0.5 && c < 1 ? std::string() : "from above 0.5 to below 1";
          },
          "(0.5, 1)"));
  cmd->add_option("--table", o->table, "Write every fit as one CSV row to this file");
  cmd->add_option("--json", o->json, "Write every fit, and the group's, as JSON to this file");
  cmd->add_option("--plots", o->plots, "Write PNG plots (and their .dat, .gp) into this folder");
  cmd->add_option("--report", o->report, "Write a markdown report to this file");
  cmd->callback([o] {
    std::vector<std::filesystem::path> files;
    for (const std::string& named : o->results) {
      std::error_code ec;
      if (!std::filesystem::is_directory(named, ec)) {
        files.emplace_back(named);
        continue;
      }
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::directory_iterator(named, ec))
        if (entry.path().extension() == ".csv") found.push_back(entry.path());
      if (found.empty()) throw FileError(named, 0, 0, "a folder with no results file (*.csv)");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    }
    std::vector<study::ResultRow> rows;
    for (const std::filesystem::path& f : files) {
      const study::ResultsFile file = study::read_results(f);
      if (!file.exists) throw FileError(f.string(), 0, 0, "file not found");
      for (const std::string& w : file.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
      rows.insert(rows.end(), file.rows.begin(), file.rows.end());
    }
    study::SummaryOptions options{o->resamples, o->seed, {}};
    options.fit.model.shape = *value_named(study::kPsychometricShapeNames, o->shape);
    options.fit.model.criterion = o->criterion;
    read_lapse(o->lapse, options.fit);
    StudyReport report;
    report.files = files;
    report.resamples = o->resamples;
    report.seed = o->seed;
    report.pooled = study::summarize(rows, o->participant, options);
    report.pooled_text = study::format_summary(report.pooled);
    // Each participant's own fit, but not a visitor's: a visitor's few trials are pooled only.
    std::vector<study::ResultRow> own;
    std::set<std::string> participants;
    for (const study::ResultRow& r : rows)
      if (!study::is_visitor_session(r.participant) && (o->participant.empty() || r.participant == o->participant)) {
        own.push_back(r);
        participants.insert(r.participant);
      }
    if (participants.size() > 1) {
      report.participants = study::summarize_participants(own, options);
      report.participants_text = study::format_participant_fits(report.participants);
    } else if (participants.size() == 1) {  // the pooled summary is theirs, unless visitors' rows were pooled too
      report.participants = {{*participants.begin(),
                              own.size() == rows.size() ? report.pooled : study::summarize(own, {}, options)}};
    }
    std::printf("%s: ", files.size() == 1 ? files.front().c_str()
                                          : (std::to_string(files.size()) + " results files").c_str());
    std::fputs(report.pooled_text.c_str(), stdout);
    std::fputs(report.participants_text.c_str(), stdout);
    report.group = study::group_thresholds(report.participants);
    std::fputs(study::format_group(report.group).c_str(), stdout);
    if (!o->table.empty()) {
      write_fit_table(report, o->table);
      std::printf("wrote %s\n", o->table.c_str());
    }
    if (!o->json.empty()) {
      write_fit_json(report, o->json);
      std::printf("wrote %s\n", o->json.c_str());
    }
    if (!o->plots.empty())
      for (const std::string& line : write_study_plots(report, o->plots)) std::printf("%s\n", line.c_str());
    if (!o->report.empty()) {
      write_study_report(report, o->report, o->plots);
      std::printf("wrote %s\n", o->report.c_str());
    }
  });
}

void add_visitors(CLI::App& study) {
  auto o = std::make_shared<SimulatedVisitors>();
  o->scene = default_scene();
  o->out_dir = "visitor-study";
  CLI::App* cmd = study.add_subcommand("visitors", "Simulate the kiosk's visitor micro-study headless");
  cmd->footer(R"(mallet study visitors --protocol config/study/visitor.toml --visitors N [--out-dir DIR]
Runs N simulated visitors through a visitor protocol (one with a [visitor] table) on a
simulated clock, as the kiosk runs a visitor who accepted its offer: the consent screen,
agreed by striking "1" (Yes), then the protocol's [visitor] trials, answered by the simulated
observer striking the answer bars through the kiosk's strike route. Each visitor is a random
session id (visitor-XXXXXXXX, from --seed) and the date; rows are appended to
DIR/visitors-YYYY-MM-DD.csv as the kiosk appends them. --abandon-after N: every second visitor
walks away after N trials (the kiosk waits the protocol's answer_timeout_s); --decline-every K:
every K-th visitor strikes "2" (No) at the consent screen and nothing is written for them.
Prints one line per visitor. Bad input: exit 2 with FILE:LINE: problem.)");
  cmd->add_option("--protocol", o->protocol, "Visitor protocol (TOML with a [visitor] table)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--visitors", o->visitors, "How many visitors")->capture_default_str()->check(CLI::Range(1, 10000));
  cmd->add_option("--out-dir", o->out_dir, "Folder of the day files")->capture_default_str();
  cmd->add_option("--abandon-after", o->abandon_after, "Every second visitor walks away after this many trials (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--decline-every", o->decline_every, "Every K-th visitor declines at the consent screen (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 10000));
  cmd->add_option("--seed", o->seed, "Seed of the session ids")->capture_default_str();
  cmd->add_option("--date", o->date, "The day the rows are dated (YYYY-MM-DD; default: today, UTC)")
      ->check(CLI::Validator(
          [](std::string& v) {
            const bool ok = v.size() == 10 && v[4] == '-' && v[7] == '-' &&
                            std::all_of(v.begin(), v.end(), [](char c) { return c == '-' || (c >= '0' && c <= '9'); });
            return ok ? std::string() : "expected YYYY-MM-DD, got \"" + v + "\"";
          },
          "YYYY-MM-DD"));
  cmd->add_option("--scene", o->scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->callback([o] {
    const std::vector<study::VisitorSessionResult> sessions = run_simulated_visitors(*o);
    std::set<std::filesystem::path> written;
    for (const study::VisitorSessionResult& v : sessions) {
      const char* how = !v.consented ? (v.abandoned ? "walked away at the consent" : "declined")
                        : v.abandoned ? "abandoned"
                                      : "completed";
      std::printf("%s: %s, %d of %d trials\n", v.id.c_str(), how, v.answered, v.planned);
      if (v.answered > 0) written.insert(v.csv);
    }
    for (const auto& f : written) std::printf("wrote %s\n", f.c_str());
  });
}

}  // namespace

void register_study(CLI::App& app) {
  auto o = std::make_shared<StudyOptions>();
  auto headless = std::make_shared<bool>(false);
  auto stop_after = std::make_shared<int>(0);
  auto window = std::make_shared<StudyWindowOptions>();
  o->config = default_settings();
  CLI::App* cmd = app.add_subcommand("study", "Run a perception study protocol (2AFC harder / name the material)");
  cmd->require_subcommand(0, 1);
  cmd->footer(R"(mallet study --protocol FILE.toml --participant ID [--windowed] [--out CSV]   (a participant)
mallet study --protocol FILE.toml --participant ID --headless [--answers FILE] [--out CSV]
mallet study summary --results CSV
mallet study visitors --protocol FILE.toml --visitors N   (the kiosk's visitor study, simulated)
Runs a psychophysics protocol (config/study/example.toml documents one): every condition
(visual_only, tactile_only, both, none) x pair or stimulus, `repetitions` times, in an order
shuffled per participant (seeded by the protocol's seed and the ID: the same ID gets the same
order) with each 2AFC pair shown in both orders equally often.
With a display (and no --headless): fullscreen (--windowed: a window), in real time. Each trial's
taps are shown by the bounce on the screen and played on the actuator (and the note, if the
protocol has sound) through the audio device (silent if none); then a prompt asks "Which tap
felt harder? Press 1 or 2" or "Which material? R rubber, W wood, ..." (the first letters of
the protocol's materials, or 1-9 when two share one). Keys pressed during the taps are ignored;
the response time runs from the end of the last tap (rows marked source=keys). Esc, Q or
closing the window stops: answered trials are kept, and the same command resumes.
A protocol with response = "strike" (config/study/strike.toml) is answered with the same
mallet on answer bars labelled "1" and "2" (or the materials' names) beside the stimulus bar;
an answer strike sounds a neutral click and no actuator signal (the protocol's [answer_strike]),
and its response time runs to the contact the strike route finds (rows marked source=strike;
headless, the simulated observer or the script strikes its answers through the same route).
The actuator_peak column is the signal sent, rendered by the same engine offline.
--headless, or without a display: on a simulated clock,
through the kiosk's own audio engine and bounce; answers come from --answers (one a line:
1 or 2, or a material name, optionally followed by a response time in ms) or, without it, from
a simulated observer (rows marked source=simulated). One CSV row per trial, fsync'd before the
next: participant,trial,condition,stimuli,answer,correct,response_time_ms, then
protocol,task,difference_pct,source,session,visual_peak_m,actuator_peak, then
actuator_onset_ms,picture_onset_ms,procedure,track_trial,reversals,estimate_pct,estimate_sd_pct,
then planned_trials,estimate_mode_pct,language (the language the trial's words were shown in),
then actuator_eq_hash,actuator_eq_utc (the actuator calibration in force; empty: none).
Run again with the same participant to resume: trials already in the CSV are skipped; an
incomplete last line (a crash while writing) is dropped with a warning naming FILE:LINE.)");
  cmd->add_option("--protocol", o->protocol, "Protocol file (TOML)")->check(CLI::ExistingFile);
  cmd->add_option("--participant", o->participant, "Participant ID (letters, digits, _ - .)");
  cmd->add_option("--out", o->out, "Results CSV, appended to (default: the protocol's `output`)");
  cmd->add_option("--answers", o->answers, "Answer script; without it a simulated observer answers");
  cmd->add_option("--audio", o->audio, "Also write this run's stimuli to a WAV file (channels as [audio.routing])");
  cmd->add_option("--scene", o->scene,
                  "Scene file (its materials and bars; default: the shipped percussion.toml, or texture.toml for "
                  "a texture_slope protocol)")
      ->check(CLI::ExistingFile);
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_flag("--headless", *headless, "Run on a simulated clock without a window (--answers or the simulated observer)");
  cmd->add_flag("--windowed", window->windowed, "With a display: a window instead of fullscreen");
  cmd->add_option("--size", window->size, "The window's size with --windowed")
      ->capture_default_str()
      ->check(pixel_size());
  cmd->add_option("--device", window->device, "Vulkan device (substring of its name; default: the settings')");
  cmd->add_option("--quit-after", window->quit_after_s, "With a display: stop as Esc would after this many seconds (0 = never)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--stop-after", *stop_after, "Test hook: end the process abruptly after N rows, as a crash would")
      ->group("");
  add_summary(*cmd);
  add_visitors(*cmd);
  cmd->callback([cmd, o, headless, stop_after, window] {
    if (cmd->get_subcommand("summary")->parsed() || cmd->get_subcommand("visitors")->parsed()) return;
    if (o->protocol.empty()) throw CLI::RequiredError("--protocol");
    if (o->participant.empty()) throw CLI::RequiredError("--participant");
    const bool windowed = !*headless && render::WindowSystem::display_available();
    if (windowed && o->answers)
      throw FileError("--answers", 0, 0, "answers come from the keys in a window; add --headless to use a script");
    if (windowed && o->audio) throw FileError("--audio", 0, 0, "a WAV of the stimuli is written only with --headless");
    if (*stop_after > 0)
      o->after_row = [n = *stop_after](int rows) {
        if (rows < n) return;
        std::fflush(stdout);
        std::_Exit(3);  // no destructors, no flushing: what a crash leaves behind
      };
    const StudyRunResult r = windowed ? run_study_window(*o, *window) : run_study(*o);
    for (const std::string& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (r.procedure == "constant")
      std::printf("participant %s: %d trials in the schedule\n", o->participant.c_str(), r.total);
    else
      std::printf("participant %s: up to %d trials (procedure = %s: each condition's track stops by its own rule)\n",
                  o->participant.c_str(), r.total, r.procedure.c_str());
    if (r.already_recorded)
      std::printf("resumed: %d trial(s) already in %s\n", r.already_recorded, r.csv.c_str());
    if (r.answered && r.simulated && r.source == "strike")
      std::printf("note: no --answers: the simulated observer answered by striking (rows marked source=strike)\n");
    else if (r.answered && r.simulated)
      std::printf("note: no --answers: the simulated observer answered (rows marked source=simulated)\n");
    std::printf("answered %d trial(s) in this run, %d correct; %d of %d recorded\n", r.answered, r.correct,
                r.already_recorded + r.answered, r.total);
    if (r.answers_ran_out) std::printf("note: the answer script ran out; run again with more answers to continue\n");
    if (windowed && r.stopped)
      std::printf("stopped before the end (Esc, Q or the window closed); run the same command to resume\n");
    for (const auto& p : r.written) std::printf("wrote %s\n", p.c_str());
    if (r.validation_failed) finish_with(1);
  });
}

}  // namespace mallet::app
