// The results file: rows survive as written; an incomplete last line (a crash during a
// write) is dropped with a warning naming FILE:LINE and cut off before the next append.
#include <cmath>
#include <fstream>
#include <iterator>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "core/study/results_csv.hpp"
#include "test_paths.hpp"

namespace mallet::study {
namespace {

namespace fs = std::filesystem;

ResultRow row(int trial, bool correct) {
  ResultRow r;
  r.participant = "P01";
  r.trial = trial;
  r.condition = "both";
  r.stimuli = "wood|metal";
  r.answer = correct ? "2" : "1";
  r.correct = correct;
  r.response_time_ms = 640.5;
  r.protocol = "t";
  r.task = "2afc_harder";
  r.difference_pct = 12.5;
  r.source = "file";
  r.session = "2026-11-23T14:00:00Z";
  r.visual_peak_m = 0.003;
  r.actuator_peak = 0.08;
  return r;
}

// The header's first `n` columns.
std::string first_columns(std::size_t n) {
  const std::string header = kResultsHeader;
  std::size_t at = 0;
  for (std::size_t i = 0; i < n && at != std::string::npos; ++i) at = header.find(',', at + (i ? 1 : 0));
  return at == std::string::npos ? header : header.substr(0, at);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ResultsCsv, HeaderStartsWithTheRequiredColumns) {
  EXPECT_EQ(std::string(kResultsHeader).rfind("participant,trial,condition,stimuli,answer,correct,response_time_ms,", 0), 0u);
  EXPECT_EQ(format_row(row(3, true)),
            "P01,3,both,wood|metal,2,1,640.500,t,2afc_harder,12.5,file,2026-11-23T14:00:00Z,0.003,0.08,,,,,,,,,,,,\n");
  EXPECT_EQ(format_row(row(3, true), 14),
            "P01,3,both,wood|metal,2,1,640.500,t,2afc_harder,12.5,file,2026-11-23T14:00:00Z,0.003,0.08\n");
  ResultRow naming = row(1, false);
  naming.difference_pct = std::nan("");
  EXPECT_NE(format_row(naming).find(",2afc_harder,,file,"), std::string::npos);  // no difference: empty
}

TEST(ResultsCsv, AppendsReadBackAndCutsAnIncompleteLastLine) {
  const fs::path csv = test::scratch_dir() / "r.csv";
  {
    ResultsWriter w(csv, read_results(csv));
    w.append(row(1, true));
    w.append(row(2, false));
  }
  // A crash in the middle of the third row's write.
  {
    std::ofstream f(csv, std::ios::app | std::ios::binary);
    f << "P01,3,both,wood|me";
  }
  const ResultsFile file = read_results(csv);
  ASSERT_TRUE(file.has_header);
  ASSERT_EQ(file.rows.size(), 2u);
  EXPECT_EQ(file.lines, (std::vector<std::uint32_t>{2, 3}));
  EXPECT_EQ(file.rows[1].trial, 2);
  EXPECT_FALSE(file.rows[1].correct);
  EXPECT_DOUBLE_EQ(file.rows[0].response_time_ms, 640.5);
  ASSERT_EQ(file.warnings.size(), 1u);
  EXPECT_EQ(file.warnings[0], csv.string() + ":4: incomplete last line ignored (the program stopped while "
                                             "writing it); that trial will be run again");
  {
    ResultsWriter w(csv, file);  // resuming cuts the fragment off before appending
    w.append(row(3, true));
  }
  const std::string text = slurp(csv);
  EXPECT_EQ(text, std::string(kResultsHeader) + "\n" + format_row(row(1, true)) + format_row(row(2, false)) +
                      format_row(row(3, true)));
  EXPECT_TRUE(read_results(csv).warnings.empty());
}

// The disk fills up while a row is written (RLIMIT_FSIZE in a child process stands in for
// ENOSPC: the kernel refuses the bytes past the limit the same way). The writer says what
// failed; every row written before is intact; the torn row is dropped on resume and its
// trial runs again.
TEST(ResultsCsv, ADiskThatFillsUpLosesNoRowAlreadyWritten) {
  const fs::path csv = test::scratch_dir() / "r.csv";
  const std::size_t header_and_two = std::string(kResultsHeader).size() + 1 + 2 * format_row(row(1, true)).size();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead of killing the process
    const rlimit limit{header_and_two + 20, header_and_two + 20};  // room for 20 bytes of a third row
    ::setrlimit(RLIMIT_FSIZE, &limit);
    ResultsWriter w(csv, read_results(csv));
    w.append(row(1, true));
    w.append(row(2, false));
    try {
      w.append(row(3, true));
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      ::_exit(what.rfind(csv.string() + ": write failed: ", 0) == 0 ? 42 : 1);
    }
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 42) << "the third row's write failed, naming the file";
  EXPECT_EQ(fs::file_size(csv), header_and_two + 20);
  const ResultsFile file = read_results(csv);
  ASSERT_EQ(file.rows.size(), 2u);
  EXPECT_EQ(file.rows[0].trial, 1);
  EXPECT_EQ(file.rows[1].trial, 2);
  ASSERT_EQ(file.warnings.size(), 1u);
  EXPECT_NE(file.warnings[0].find(":4: incomplete last line ignored"), std::string::npos) << file.warnings[0];
}

TEST(ResultsCsv, AHalfWrittenHeaderStartsTheFileAgain) {
  const fs::path csv = test::scratch_dir() / "r.csv";
  { std::ofstream(csv) << "participant,tri"; }
  const ResultsFile file = read_results(csv);
  EXPECT_FALSE(file.has_header);
  EXPECT_EQ(file.warnings.size(), 1u);
  { ResultsWriter w(csv, file); }
  EXPECT_EQ(slurp(csv), std::string(kResultsHeader) + "\n");
}

TEST(ResultsCsv, TheCuesOnsetsRoundTripAndAFileFromBeforeThemResumesWithoutThem) {
  const fs::path dir = test::scratch_dir();
  ResultRow timed = row(1, true);
  timed.actuator_onset_ms = 1.5;
  timed.picture_onset_ms = 34.25;
  {
    ResultsWriter w(dir / "new.csv", read_results(dir / "new.csv"));
    w.append(timed);
  }
  const ResultsFile now = read_results(dir / "new.csv");
  EXPECT_EQ(now.header, kResultsHeader);
  ASSERT_EQ(now.rows.size(), 1u);
  EXPECT_DOUBLE_EQ(now.rows[0].actuator_onset_ms, 1.5);
  EXPECT_DOUBLE_EQ(now.rows[0].picture_onset_ms, 34.25);
  // A file begun by an older version: its header stays, and a resumed session appends its
  // rows in the same columns (the onsets read back as not recorded).
  {
    std::ofstream old(dir / "old.csv");
    old << kResultsHeaderWithoutTiming << "\n" << format_row(row(1, true), 14);
  }
  {
    ResultsWriter w(dir / "old.csv", read_results(dir / "old.csv"));
    w.append(timed);
  }
  const ResultsFile resumed = read_results(dir / "old.csv");
  EXPECT_EQ(resumed.header, kResultsHeaderWithoutTiming);
  ASSERT_EQ(resumed.rows.size(), 2u);
  EXPECT_TRUE(std::isnan(resumed.rows[1].actuator_onset_ms));
  EXPECT_EQ(std::string(kResultsHeader).rfind(kResultsHeaderWithoutTiming, 0), 0u) << "the new columns come last";
}

TEST(ResultsCsv, EachVersionsHeaderResumesInItsOwnColumnsAndPlannedTrialsRoundTrip) {
  EXPECT_EQ(results_columns(kResultsHeader), kResultsColumns);
  EXPECT_EQ(results_columns(kResultsHeaderWithoutTiming), 14u);
  const std::string header = kResultsHeader;
  const std::string before_planned = header.substr(0, header.find(",planned_trials"));
  EXPECT_EQ(results_columns(before_planned), 21u);
  EXPECT_EQ(results_columns("participant,trial,condition,stimuli,answer,correct,response_time_ms"), 0u);
  EXPECT_EQ(results_columns(before_planned + ",planned"), 0u) << "a column cut short is not ours";
  EXPECT_EQ(results_columns(std::string(kResultsHeader) + ",more"), 0u);
  const fs::path dir = test::scratch_dir();
  ResultRow planned = row(1, true);
  planned.planned_trials = 6;
  { std::ofstream(dir / "v21.csv") << before_planned << "\n" << format_row(row(1, true), 21); }
  {
    ResultsWriter w(dir / "v21.csv", read_results(dir / "v21.csv"));
    w.append(planned);
    ResultsWriter n(dir / "new.csv", read_results(dir / "new.csv"));
    n.append(planned);
  }
  const ResultsFile old = read_results(dir / "v21.csv");
  EXPECT_EQ(old.header, before_planned);
  ASSERT_EQ(old.rows.size(), 2u);
  EXPECT_EQ(old.rows[1].planned_trials, 0) << "not in that file's columns";
  const ResultsFile now = read_results(dir / "new.csv");
  ASSERT_EQ(now.rows.size(), 1u);
  EXPECT_EQ(now.rows[0].planned_trials, 6);
}

TEST(ResultsCsv, AnAdaptiveTracksStateRoundTrips) {
  const fs::path dir = test::scratch_dir();
  ResultRow r = row(7, true);
  r.procedure = "staircase";
  r.track_trial = 3;
  r.reversals = 2;
  r.estimate_pct = 12.25;
  {
    ResultsWriter w(dir / "r.csv", read_results(dir / "r.csv"));
    w.append(r);
  }
  const ResultsFile back = read_results(dir / "r.csv");
  ASSERT_EQ(back.rows.size(), 1u);
  EXPECT_EQ(back.rows[0].procedure, "staircase");
  EXPECT_EQ(back.rows[0].track_trial, 3);
  EXPECT_EQ(back.rows[0].reversals, 2);
  EXPECT_EQ(back.rows[0].estimate_pct, 12.25);
  EXPECT_TRUE(std::isnan(back.rows[0].estimate_sd_pct));
  std::string text = slurp(dir / "r.csv");
  text.replace(text.find(",staircase,"), 11, ",bisection,");
  { std::ofstream(dir / "bad.csv") << text; }
  EXPECT_EQ(std::string(test::file_error_of([&] { read_results(dir / "bad.csv"); }).what()),
            (dir / "bad.csv").string() + ":2: procedure: \"bisection\" is not constant, staircase, quest or quest_plus");
}

TEST(ResultsCsv, EstimatesAreWrittenInFullAndQuestsModeComesLast) {
  // The estimates are written as the shortest decimal that reads back as the same double (4
  // significant digits before), and QUEST's posterior mode is a column of its own (the 23rd).
  const std::string before_language = first_columns(23);
  EXPECT_EQ(before_language.substr(before_language.rfind(',') + 1), "estimate_mode_pct");
  const fs::path dir = test::scratch_dir();
  ResultRow r = row(4, true);
  r.procedure = "quest";
  r.track_trial = 2;
  r.estimate_pct = 0.1 + 0.2;  // 0.30000000000000004: 17 digits
  r.estimate_sd_pct = std::nextafter(14.0, 15.0);  // 14.000000000000002: one ulp above 14
  r.estimate_mode_pct = 1.0 / 3.0;
  const std::string line = format_row(r);
  EXPECT_NE(line.find(",quest,2,,0.30000000000000004,14.000000000000002,,0.3333333333333333,"), std::string::npos)
      << line;
  ResultRow whole = r;
  whole.estimate_pct = 20;
  EXPECT_NE(format_row(whole).find(",quest,2,,20,"), std::string::npos) << "no trailing zeros";
  {
    ResultsWriter w(dir / "r.csv", read_results(dir / "r.csv"));
    w.append(r);
    w.append(row(5, false));  // a constant trial: no estimate, no mode
  }
  const ResultsFile back = read_results(dir / "r.csv");
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_EQ(back.rows[0].estimate_pct, 0.1 + 0.2);
  EXPECT_EQ(back.rows[0].estimate_sd_pct, std::nextafter(14.0, 15.0));
  EXPECT_EQ(back.rows[0].estimate_mode_pct, 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(back.rows[1].estimate_mode_pct));
  // A file from before the mode (22 columns) reads, its rows without a mode, and a session
  // resumed in it appends rows of its own 22 columns.
  const std::string before_mode = before_language.substr(0, before_language.rfind(','));
  EXPECT_EQ(results_columns(before_mode), 22u);
  { std::ofstream(dir / "v22.csv") << before_mode << "\n" << format_row(r, 22); }
  {
    ResultsWriter w(dir / "v22.csv", read_results(dir / "v22.csv"));
    w.append(r);
  }
  const ResultsFile old = read_results(dir / "v22.csv");
  EXPECT_EQ(old.header, before_mode);
  ASSERT_EQ(old.rows.size(), 2u);
  for (const ResultRow& o : old.rows) {
    EXPECT_EQ(o.estimate_pct, 0.1 + 0.2);
    EXPECT_TRUE(std::isnan(o.estimate_mode_pct)) << "not in that file's columns";
  }
  EXPECT_EQ(slurp(dir / "v22.csv"), before_mode + "\n" + format_row(r, 22) + format_row(r, 22));
  // And a row of the 4-digit era still reads.
  {
    std::ofstream(dir / "v4.csv") << before_mode << "\n"
                                  << "P01,1,both,a|b,2,1,5,t,2afc_harder,1,file,s,0,0,1,20,quest,1,,12.35,3.142,40\n";
  }
  const ResultsFile four = read_results(dir / "v4.csv");
  ASSERT_EQ(four.rows.size(), 1u);
  EXPECT_EQ(four.rows[0].estimate_pct, 12.35);
  EXPECT_EQ(four.rows[0].estimate_sd_pct, 3.142);
}

TEST(ResultsCsv, ABadLineInTheMiddleIsAFileError) {
  const fs::path csv = test::scratch_dir() / "r.csv";
  { std::ofstream(csv) << kResultsHeader << "\n" << "P01,x,both,a|b,1,1,5,t,2afc_harder,1,file,s,0,0,1,20,constant,,,,,,,,,\n"; }
  EXPECT_EQ(std::string(test::file_error_of([&] { read_results(csv); }).what()),
            csv.string() + ":2: trial: \"x\" is not a number");
  { std::ofstream(csv) << "participant,trial\nP01,1\n"; }
  EXPECT_EQ(std::string(test::file_error_of([&] { read_results(csv); }).what()),
            csv.string() + ":1: missing column \"condition\" (expected a header starting "
                           "participant,trial,condition,stimuli,answer,correct,response_time_ms)");
}

TEST(ResultsCsv, TheLanguageTheWordsWereShownInIsTheLastColumnAndAnOlderFileResumesWithoutIt) {
  // A visitor shown the study in German (issue 30): the row says so; a file begun before the
  // column reads, its rows without a language, and a session resumed in it keeps its columns.
  const std::string with_language = first_columns(24);
  EXPECT_EQ(with_language.substr(with_language.rfind(',') + 1), "language");
  const std::string before_language = first_columns(23);
  EXPECT_EQ(results_columns(before_language), 23u);
  const fs::path dir = test::scratch_dir();
  ResultRow r = row(1, true);
  r.language = "de";
  EXPECT_TRUE(format_row(r, 24).ends_with(",de\n")) << format_row(r, 24);
  {
    ResultsWriter w(dir / "r.csv", read_results(dir / "r.csv"));
    w.append(r);
  }
  const ResultsFile back = read_results(dir / "r.csv");
  ASSERT_EQ(back.rows.size(), 1u);
  EXPECT_EQ(back.rows[0].language, "de");
  { std::ofstream(dir / "v23.csv") << before_language << "\n" << format_row(r, 23); }
  {
    ResultsWriter w(dir / "v23.csv", read_results(dir / "v23.csv"));
    w.append(r);
  }
  const ResultsFile old = read_results(dir / "v23.csv");
  ASSERT_EQ(old.rows.size(), 2u);
  for (const ResultRow& o : old.rows) EXPECT_EQ(o.language, "") << "not in that file's columns";
  EXPECT_EQ(slurp(dir / "v23.csv"), before_language + "\n" + format_row(r, 23) + format_row(r, 23));
}

TEST(ResultsCsv, TheActuatorCalibrationInForceIsTheLastTwoColumnsAndAnOlderFileResumesWithoutThem) {
  // A study run with the actuator equalised (issue 32): each row names the calibration by its
  // identity and date; a file begun before the columns keeps its 24.
  const std::string header = kResultsHeader;
  EXPECT_TRUE(header.ends_with(",language,actuator_eq_hash,actuator_eq_utc")) << header;
  const fs::path dir = test::scratch_dir();
  ResultRow r = row(1, true);
  r.actuator_eq_hash = "19c52f955d6bb599";
  r.actuator_eq_utc = "2026-12-06T08:39:03Z";
  EXPECT_TRUE(format_row(r).ends_with(",19c52f955d6bb599,2026-12-06T08:39:03Z\n")) << format_row(r);
  {
    ResultsWriter w(dir / "r.csv", read_results(dir / "r.csv"));
    w.append(r);
    w.append(row(2, false));  // none in force
  }
  const ResultsFile back = read_results(dir / "r.csv");
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_EQ(back.rows[0].actuator_eq_hash, "19c52f955d6bb599");
  EXPECT_EQ(back.rows[0].actuator_eq_utc, "2026-12-06T08:39:03Z");
  EXPECT_EQ(back.rows[1].actuator_eq_hash, "");
  const std::string v24 = first_columns(24);
  { std::ofstream(dir / "v24.csv") << v24 << "\n" << format_row(r, 24); }
  {
    ResultsWriter w(dir / "v24.csv", read_results(dir / "v24.csv"));
    w.append(r);
  }
  const ResultsFile old = read_results(dir / "v24.csv");
  ASSERT_EQ(old.rows.size(), 2u);
  for (const ResultRow& o : old.rows) EXPECT_EQ(o.actuator_eq_hash, "") << "not in that file's columns";
  EXPECT_EQ(slurp(dir / "v24.csv"), v24 + "\n" + format_row(r, 24) + format_row(r, 24));
}

}  // namespace
}  // namespace mallet::study
