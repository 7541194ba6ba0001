// `mallet study` end to end, as a researcher runs it: a whole short protocol headless; a
// crash mid-session and its resumption; the summary; bad input exits 2 with one line.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "core/study/results_csv.hpp"
#include "core/study/study_summary.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;
using study::ResultRow;

std::string example() { return (test::config_dir() / "study" / "example.toml").string(); }

std::string study_args(const fs::path& csv, const std::string& participant = "P01") {
  return "study --headless --protocol " + example() + " --participant " + participant + " --out " + csv.string();
}

std::vector<ResultRow> rows_of(const fs::path& csv) { return study::read_results(csv).rows; }

TEST(StudyCli, RunsTheExampleProtocolHeadlessWithTheSimulatedObserver) {
  const fs::path dir = test::scratch_dir();
  const test::CliResult r = test::run_mallet(study_args(dir / "r.csv") + " --audio " + (dir / "a.wav").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("participant P01: 32 trials in the schedule"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("source=simulated"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "a.wav"));

  const std::vector<ResultRow> rows = rows_of(dir / "r.csv");
  ASSERT_EQ(rows.size(), 32u);
  std::map<std::string, int> per_condition;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ResultRow& row = rows[i];
    EXPECT_EQ(row.trial, static_cast<int>(i + 1));
    EXPECT_EQ(row.participant, "P01");
    EXPECT_EQ(row.source, "simulated");
    EXPECT_TRUE(row.answer == "1" || row.answer == "2");
    ++per_condition[row.condition];
    // What the condition presented, measured on the rendered output: the bounce only
    // with vision, the actuator signal only with touch.
    const bool visual = row.condition == "visual_only" || row.condition == "both";
    const bool tactile = row.condition == "tactile_only" || row.condition == "both";
    EXPECT_EQ(row.visual_peak_m > 1e-4, visual) << row.trial << " " << row.condition << " " << row.visual_peak_m;
    EXPECT_EQ(row.visual_peak_m == 0.0, !visual);
    EXPECT_EQ(row.actuator_peak > 1e-3, tactile) << row.trial << " " << row.condition << " " << row.actuator_peak;
    EXPECT_EQ(row.actuator_peak == 0.0, !tactile);
    // The strike route's cue times, after the contact: heard on it ([timing] align = asap),
    // shown by the simulated 60 Hz display's first frame that has the bounce (2–3 periods).
    EXPECT_GE(row.actuator_onset_ms, 0.0) << row.trial;
    EXPECT_LT(row.actuator_onset_ms, 1.0) << row.trial;
    EXPECT_GE(row.picture_onset_ms, 33.0) << row.trial;
    EXPECT_LE(row.picture_onset_ms, 50.1) << row.trial;
  }
  EXPECT_EQ(per_condition, (std::map<std::string, int>{{"both", 8}, {"none", 8}, {"tactile_only", 8}, {"visual_only", 8}}));

  const test::CliResult s = test::run_mallet("study summary --results " + (dir / "r.csv").string());
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_NE(s.output.find("32 trials, 1 participant"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("visual_only          8"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("psychometric fit"), std::string::npos) << s.output;

  // Running again: nothing left to do, nothing added.
  const test::CliResult again = test::run_mallet(study_args(dir / "r.csv"));
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("answered 0 trial(s) in this run, 0 correct; 32 of 32 recorded"), std::string::npos)
      << again.output;
  EXPECT_EQ(rows_of(dir / "r.csv").size(), 32u);
}

TEST(StudyCli, ACrashMidSessionLosesNothingAndTheSessionResumes) {
  const fs::path dir = test::scratch_dir();
  const fs::path csv = dir / "r.csv";
  // P02 first, uninterrupted, in the same file: a resume must not touch another's rows.
  ASSERT_EQ(test::run_mallet(study_args(csv, "P02")).status, 0);
  // P01 is cut off abruptly after 5 trials ...
  const test::CliResult crashed = test::run_mallet(study_args(csv) + " --stop-after 5");
  ASSERT_EQ(crashed.status, 3) << crashed.output;
  std::vector<ResultRow> rows = rows_of(csv);
  ASSERT_EQ(rows.size(), 32u + 5u);
  // ... and, as if it died in the middle of writing the sixth, a fragment of a row.
  { std::ofstream(csv, std::ios::app) << "P01,6,bo"; }

  const test::CliResult resumed = test::run_mallet(study_args(csv));
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("warning: " + csv.string() + ":39: incomplete last line ignored"), std::string::npos)
      << resumed.output;
  EXPECT_NE(resumed.output.find("resumed: 5 trial(s) already in"), std::string::npos) << resumed.output;
  EXPECT_NE(resumed.output.find("answered 27 trial(s) in this run"), std::string::npos) << resumed.output;

  const study::ResultsFile file = study::read_results(csv);
  EXPECT_TRUE(file.warnings.empty());
  std::map<std::string, std::multiset<int>> trials;
  for (const ResultRow& row : file.rows) trials[row.participant].insert(row.trial);
  for (const char* who : {"P01", "P02"}) {
    ASSERT_EQ(trials[who].size(), 32u) << who;
    for (int n = 1; n <= 32; ++n) EXPECT_EQ(trials[who].count(n), 1u) << who << " trial " << n;
  }

  // The resumed session is the session that was interrupted: same trials, same answers.
  const fs::path whole = dir / "whole.csv";
  ASSERT_EQ(test::run_mallet(study_args(whole)).status, 0);
  std::map<int, ResultRow> uninterrupted;
  for (const ResultRow& row : rows_of(whole)) uninterrupted[row.trial] = row;
  for (const ResultRow& row : file.rows) {
    if (row.participant != "P01") continue;
    const ResultRow& w = uninterrupted.at(row.trial);
    EXPECT_EQ(row.condition + row.stimuli + row.answer, w.condition + w.stimuli + w.answer) << row.trial;
    EXPECT_DOUBLE_EQ(row.response_time_ms, w.response_time_ms);
  }
}

TEST(StudyCli, AnswersFromAFileAndTheirMistakes) {
  const fs::path dir = test::scratch_dir();
  const std::string protocol = (test::config_dir() / "study" / "name_material.toml").string();
  const fs::path answers = dir / "answers.txt";
  {
    std::ofstream f(answers);
    f << "# one answer per trial\n";
    for (int i = 0; i < 20; ++i) f << (i % 2 ? "wood" : "metal 512.5") << "\n";
  }
  const std::string args = "study --headless --protocol " + protocol + " --participant P7 --out " +
                           (dir / "n.csv").string() + " --answers " + answers.string();
  const test::CliResult r = test::run_mallet(args);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("answered 20 trial(s) in this run"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the answer script ran out"), std::string::npos) << r.output;
  std::vector<ResultRow> rows = rows_of(dir / "n.csv");
  ASSERT_EQ(rows.size(), 20u);
  EXPECT_EQ(rows[0].answer, "metal");
  EXPECT_DOUBLE_EQ(rows[0].response_time_ms, 512.5);
  EXPECT_DOUBLE_EQ(rows[1].response_time_ms, 800.0);
  EXPECT_EQ(rows[0].source, "file");
  for (const ResultRow& row : rows) EXPECT_EQ(row.correct, row.answer == row.stimuli);  // stimulus = material here

  { std::ofstream(answers) << "wood\n  glass\n"; }
  const test::CliResult bad = test::run_mallet(args);
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.output, "mallet: " + answers.string() +
                            ":2:3: \"glass\" is not an answer of this protocol (wood, metal)\n");
}

TEST(StudyCli, BadInputIsOneLineAndExitStatus2) {
  const fs::path dir = test::scratch_dir();
  const fs::path protocol = dir / "bad.toml";
  {
    std::ofstream f(protocol);
    f << "name = \"x\"\ntask = \"2afc_harder\"\nconditions = [\"both\"]\nrepetitions = 2\nseed = 1\n"
         "[[stimulus]]\nname = \"a\"\nmaterial = \"glass\"\n";
  }
  const std::string base = "study --headless --out " + (dir / "r.csv").string() + " --protocol ";
  const test::CliResult r = test::run_mallet(base + protocol.string() + " --participant P01");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "mallet: " + protocol.string() +
                          ":8:12: stimulus[0].material: unknown material \"glass\" (the scene has: wood, metal)\n");
  EXPECT_FALSE(fs::exists(dir / "r.csv"));

  const test::CliResult who = test::run_mallet(base + example() + " --participant 'P 1'");
  EXPECT_EQ(who.status, 2);
  EXPECT_EQ(who.output, "mallet: --participant: \"P 1\" must be 1-64 letters, digits, '_', '-' or '.'\n");

  // A results file from another protocol: refused, not mixed.
  ASSERT_EQ(test::run_mallet(base + example() + " --participant P01 --stop-after 1").status, 3);
  const std::string other = (test::config_dir() / "study" / "name_material.toml").string();
  const test::CliResult mixed = test::run_mallet(base + other + " --participant P01");
  EXPECT_EQ(mixed.status, 2) << mixed.output;
  EXPECT_NE(mixed.output.find((dir / "r.csv").string() + ":2: trial 1 of P01 is "), std::string::npos) << mixed.output;

  const test::CliResult missing = test::run_mallet("study summary --results " + (dir / "nope.csv").string());
  EXPECT_EQ(missing.status, 2);
  EXPECT_EQ(missing.output, "mallet: " + (dir / "nope.csv").string() + ": file not found\n");
}

TEST(StudyCli, TheSummaryPoolsManyFilesAndFoldersAndFitsEachParticipant) {
  // Two participants' sessions in two files of one folder: pooled, then each one's fit.
  const fs::path dir = test::scratch_dir();
  fs::create_directories(dir / "results");
  for (const char* p : {"P01", "P02"})
    ASSERT_EQ(test::run_mallet(study_args(dir / "results" / (std::string(p) + ".csv"), p)).status, 0);
  const test::CliResult folder = test::run_mallet("study summary --results " + (dir / "results").string());
  ASSERT_EQ(folder.status, 0) << folder.output;
  EXPECT_NE(folder.output.find("2 results files: 64 trials, 2 participants"), std::string::npos) << folder.output;
  EXPECT_NE(folder.output.find("per participant, the same fit:"), std::string::npos) << folder.output;
  for (const char* p : {"P01", "P02"})
    for (const char* c : {"visual_only", "tactile_only", "both", "none"}) {
      char prefix[64];
      std::snprintf(prefix, sizeof prefix, "\n%-12s %-14s", p, c);
      EXPECT_NE(folder.output.find(prefix), std::string::npos) << p << " " << c << "\n" << folder.output;
    }
  // The same two files named one by one: the same summary.
  const test::CliResult files = test::run_mallet("study summary --results " + (dir / "results" / "P01.csv").string() +
                                                 " " + (dir / "results" / "P02.csv").string());
  ASSERT_EQ(files.status, 0) << files.output;
  EXPECT_EQ(files.output, folder.output);
  // One participant's rows only: no per-participant section.
  const test::CliResult one =
      test::run_mallet("study summary --participant P02 --results " + (dir / "results").string());
  ASSERT_EQ(one.status, 0) << one.output;
  EXPECT_NE(one.output.find("32 trials, 1 participant"), std::string::npos) << one.output;
  EXPECT_EQ(one.output.find("per participant"), std::string::npos) << one.output;
  // A folder with no results file is one line and exit 2.
  fs::create_directories(dir / "empty");
  const test::CliResult empty = test::run_mallet("study summary --results " + (dir / "empty").string());
  EXPECT_EQ(empty.status, 2);
  EXPECT_EQ(empty.output, "mallet: " + (dir / "empty").string() + ": a folder with no results file (*.csv)\n");
}

TEST(StudyCli, TheSummaryGivesIntervalsPlotsAndAReport) {
  // Three simulated participants: each fit with its 95 % interval, the plots as PNGs with
  // their data, and a report embedding them; the same seed gives the same intervals.
  const fs::path dir = test::scratch_dir();
  fs::create_directories(dir / "results");
  for (const char* p : {"P01", "P02", "P03"})
    ASSERT_EQ(test::run_mallet(study_args(dir / "results" / (std::string(p) + ".csv"), p)).status, 0);
  const std::string base = "study summary --bootstrap 200 --results " + (dir / "results").string();
  const test::CliResult s =
      test::run_mallet(base + " --plots " + (dir / "plots").string() + " --report " + (dir / "report.md").string());
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_NE(s.output.find("threshold_95ci"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("95 % intervals: parametric bootstrap, 200 resamples"), std::string::npos) << s.output;
  for (const char* plot : {"psychometric", "thresholds", "response_times"}) {
    for (const char* ext : {".dat", ".gp"})
      EXPECT_GT(fs::file_size(dir / "plots" / (std::string(plot) + ext)), 20u) << plot << ext;
    const fs::path png = dir / "plots" / (std::string(plot) + ".png");
    ASSERT_TRUE(fs::exists(png)) << s.output;  // gnuplot-nox is a build dependency
    std::ifstream f(png, std::ios::binary);
    char magic[8]{};
    f.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG") << png;
    EXPECT_NE(s.output.find("wrote " + png.string()), std::string::npos) << s.output;
  }
  std::ifstream in(dir / "report.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("3 results files, 96 trials, 3 participants"), std::string::npos) << md;
  EXPECT_NE(md.find("](plots/psychometric.png)"), std::string::npos) << md;
  EXPECT_NE(md.find("](plots/thresholds.png)"), std::string::npos) << md;
  EXPECT_NE(md.find("per participant, the same fit:"), std::string::npos) << md;
  // The intervals are the data's and the seed's: again the same, another seed not.
  const test::CliResult again = test::run_mallet(base);
  const test::CliResult other = test::run_mallet(base + " --seed 2");
  ASSERT_EQ(again.status, 0);
  EXPECT_EQ(s.output.substr(0, s.output.find("wrote")), again.output);
  EXPECT_NE(other.output, again.output);
  // Too few resamples for a 2.5th percentile: refused by the flag's own check.
  const test::CliResult few = test::run_mallet(base + " --bootstrap 5");
  EXPECT_EQ(few.status, 2) << few.output;
  EXPECT_NE(few.output.find("--bootstrap"), std::string::npos) << few.output;
}

TEST(StudyCli, TheSummaryNeverPrintsABoundAsAnEstimateAndWritesItsFitsAsATableAndJson) {
  // The shipped example protocol's P01 (2 trials a level): `both` is answered right every
  // time, which has no finite threshold; it used to print the search's edge, −20.000.
  const fs::path dir = test::scratch_dir();
  ASSERT_EQ(test::run_mallet(study_args(dir / "p01.csv")).status, 0);
  const std::string base = "study summary --bootstrap 100 --results " + (dir / "p01.csv").string();
  const test::CliResult s = test::run_mallet(base + " --table " + (dir / "fits.csv").string() + " --json " +
                                             (dir / "fits.json").string());
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_EQ(s.output.find("-20.000"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("threshold below the tested range: no estimate"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("goodness of fit: deviance"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("wrote " + (dir / "fits.csv").string()), std::string::npos) << s.output;
  std::ifstream table(dir / "fits.csv");
  std::string header, line;
  std::getline(table, header);
  EXPECT_EQ(header, study::kFitTableColumns);
  int rows = 0;
  bool both_empty = false;
  while (std::getline(table, line)) {
    ++rows;
    if (line.rfind("both,pooled,logistic,0.75,0,4,8,,", 0) == 0) both_empty = true;
  }
  EXPECT_EQ(rows, 8) << "one per condition pooled, and the same for the one participant";
  EXPECT_TRUE(both_empty) << "no threshold: an empty cell, not a number";
  std::ifstream json_in(dir / "fits.json");
  const std::string json((std::istreambuf_iterator<char>(json_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"threshold_pct\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"threshold_below_range\""), std::string::npos) << json;

  // Another shape, the lapse fitted, another criterion: said in the header line.
  const test::CliResult w = test::run_mallet(base + " --shape weibull --lapse fit --criterion 0.8");
  ASSERT_EQ(w.status, 0) << w.output;
  EXPECT_NE(w.output.find("(weibull), threshold at 0.8 correct without lapses, lapse fitted within [0, 0.06]"),
            std::string::npos)
      << w.output;
  // Values out of range: exit 2 with one line naming the flag.
  for (const char* bad : {" --lapse 0.7", " --lapse maybe", " --shape cubic", " --criterion 0.4"}) {
    const test::CliResult r = test::run_mallet(base + bad);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(bad).substr(1, std::string(bad).find(' ', 1) - 1)), std::string::npos)
        << bad << ": " << r.output;
  }
}

TEST(StudyCli, AStaircaseRunsHeadlessResumesAfterACrashAndIsSummarised) {
  // The shipped staircase protocol with the simulated observer: interleaved tracks, rows
  // recording each track's state; killed after 20 rows and run again, it ends with the rows
  // an uninterrupted run writes (the same trials, answers and states).
  const fs::path dir = test::scratch_dir();
  const std::string protocol = (test::config_dir() / "study" / "staircase.toml").string();
  const std::string base = "study --headless --protocol " + protocol + " --participant P01 --out ";
  const test::CliResult whole = test::run_mallet(base + (dir / "whole.csv").string());
  ASSERT_EQ(whole.status, 0) << whole.output;
  EXPECT_NE(whole.output.find("participant P01: up to 240 trials (procedure = staircase"), std::string::npos)
      << whole.output;
  EXPECT_EQ(test::run_mallet(base + (dir / "crash.csv").string() + " --stop-after 20").status, 3);
  EXPECT_EQ(rows_of(dir / "crash.csv").size(), 20u);
  const test::CliResult resumed = test::run_mallet(base + (dir / "crash.csv").string());
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resumed: 20 trial(s) already in"), std::string::npos) << resumed.output;
  const std::vector<ResultRow> a = rows_of(dir / "whole.csv"), b = rows_of(dir / "crash.csv");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 60u);
  std::map<std::string, double> last_estimate;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].condition, b[i].condition) << i;
    EXPECT_EQ(a[i].stimuli, b[i].stimuli) << i;
    EXPECT_EQ(a[i].answer, b[i].answer) << i;
    EXPECT_EQ(a[i].procedure, "staircase");
    EXPECT_EQ(a[i].track_trial, b[i].track_trial) << i;
    EXPECT_EQ(a[i].reversals, b[i].reversals) << i;
    EXPECT_EQ(std::isnan(a[i].estimate_pct), std::isnan(b[i].estimate_pct)) << i;
    if (!std::isnan(a[i].estimate_pct)) {
      EXPECT_EQ(a[i].estimate_pct, b[i].estimate_pct) << i;
      last_estimate[a[i].condition] = a[i].estimate_pct;
    }
  }
  // The tracks settle in the observer's order of thresholds (both 8 %, visual_only 20 %).
  ASSERT_EQ(last_estimate.size(), 3u);
  EXPECT_LT(last_estimate["both"], last_estimate["visual_only"]);
  // The same protocol again: nothing left to run.
  const test::CliResult again = test::run_mallet(base + (dir / "whole.csv").string());
  EXPECT_NE(again.output.find("answered 0 trial(s) in this run"), std::string::npos) << again.output;
  // The summary reports each track's final estimate and plots the tracks.
  const test::CliResult summary = test::run_mallet("study summary --bootstrap 0 --results " +
                                                   (dir / "whole.csv").string() + " --plots " + (dir / "plots").string());
  ASSERT_EQ(summary.status, 0) << summary.output;
  EXPECT_NE(summary.output.find("adaptive tracks: the estimate at each track's last trial"), std::string::npos)
      << summary.output;
  char both[64];
  std::snprintf(both, sizeof both, "%-14s %-10s %6d %13.2f", "both", "staircase", 1, last_estimate["both"]);
  EXPECT_NE(summary.output.find(both), std::string::npos) << both << "\n" << summary.output;
  EXPECT_TRUE(fs::exists(dir / "plots" / "tracks.png")) << summary.output;
}

}  // namespace
}  // namespace mallet::app
