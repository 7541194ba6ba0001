// The visitor micro-study headless, through the kiosk's strike route: simulated visitors who
// accept, agree on the consent screen and strike their answers; one who walks away mid-way
// leaves the trials done in the day's file; one who declines leaves nothing; and the file
// holds nothing about a visitor but a random id, the date and the answers.
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "app/study/visitor_study.hpp"
#include "core/study/results_csv.hpp"
#include "core/study/study_summary.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

//! "visitor-" and 8 lower-case hex digits.
bool is_random_id(const std::string& id) {
  return id.size() == 16 && id.starts_with("visitor-") &&
         id.find_first_not_of("0123456789abcdef", 8) == std::string::npos;
}

SimulatedVisitors visitors(const fs::path& dir, int n) {
  SimulatedVisitors o;
  o.protocol = test::config_dir() / "study" / "visitor.toml";
  o.scene = test::percussion_scene();
  o.out_dir = dir / "visitors";
  o.visitors = n;
  o.seed = 11;
  o.date = "2026-11-27";
  return o;
}

TEST(VisitorStudy, VisitorsAgreeAnswerByStrikingAndLeaveOnlyAnIdADateAndTheirAnswers) {
  const fs::path dir = test::scratch_dir();
  SimulatedVisitors o = visitors(dir, 4);
  o.abandon_after = 2;  // visitors 2 and 4 walk away after 2 trials
  o.decline_every = 3;  // visitor 3 declines
  const std::vector<study::VisitorSessionResult> sessions = run_simulated_visitors(o);
  ASSERT_EQ(sessions.size(), 4u);
  EXPECT_TRUE(sessions[0].consented && !sessions[0].abandoned);
  EXPECT_EQ(sessions[0].answered, 6);
  EXPECT_TRUE(sessions[1].consented && sessions[1].abandoned);
  EXPECT_EQ(sessions[1].answered, 2);
  EXPECT_FALSE(sessions[2].consented);
  EXPECT_FALSE(sessions[2].abandoned) << "declining is not walking away";
  EXPECT_EQ(sessions[2].answered, 0);
  EXPECT_EQ(sessions[3].answered, 2);
  std::set<std::string> ids;
  for (const study::VisitorSessionResult& s : sessions) ids.insert(s.id);
  EXPECT_EQ(ids.size(), 4u) << "each visitor a new id";

  const fs::path day = dir / "visitors" / "visitors-2026-11-27.csv";
  ASSERT_EQ(sessions[0].csv, day);
  const study::ResultsFile file = study::read_results(day);
  EXPECT_EQ(file.header, study::kResultsHeader);
  ASSERT_EQ(file.rows.size(), 6u + 2u + 2u) << "the walked-away visitors' trials are kept";
  for (const study::ResultRow& r : file.rows) {
    EXPECT_TRUE(is_random_id(r.participant)) << r.participant;
    EXPECT_EQ(r.session, "2026-11-27") << "the date, no time of day";
    EXPECT_EQ(r.source, "strike");
    EXPECT_EQ(r.planned_trials, 6);
    EXPECT_NE(r.participant, sessions[2].id) << "the one who declined left nothing";
  }
  // Nothing else in the file: every field of every line is one of the row's own columns.
  std::ifstream in(day);
  std::string line;
  std::getline(in, line);
  for (std::size_t n = 0; std::getline(in, line); ++n)
    EXPECT_EQ(line + "\n", study::format_row(file.rows[n])) << n;

  // The summary pools them: two completed (visitor 1, and none other), two abandoned.
  const study::StudySummary summary = study::summarize(file.rows);
  EXPECT_EQ(summary.visitor_sessions_completed, 1);
  EXPECT_EQ(summary.visitor_sessions_abandoned, 2);

  // The next day's visitors go to the next day's file; the same day's append.
  o.date = "2026-11-28";
  o.visitors = 1;
  o.seed = 12;
  run_simulated_visitors(o);
  EXPECT_EQ(study::read_results(dir / "visitors" / "visitors-2026-11-28.csv").rows.size(), 6u);
  EXPECT_EQ(study::read_results(day).rows.size(), 10u);
}

TEST(VisitorStudy, AProtocolWithoutAVisitorTableIsRefusedWhereItIsNamed) {
  const fs::path dir = test::scratch_dir();
  SimulatedVisitors o = visitors(dir, 1);
  o.protocol = test::config_dir() / "study" / "strike.toml";
  try {
    run_simulated_visitors(o);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_EQ(std::string(e.what()), "--protocol: names " + o.protocol.string() +
                                         ", which has no [visitor] table (config/study/visitor.toml has one)");
  }
}

}  // namespace
}  // namespace mallet::app
