// The visitor micro-study headless, through the kiosk's strike route: simulated visitors who
// accept, agree on the consent screen and strike their answers; one who walks away mid-way
// leaves the trials done in the day's file; one who declines leaves nothing; and the file
// holds nothing about a visitor but a random id, the date and the answers.
#include <algorithm>
#include <fstream>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "app/study/study_stimuli.hpp"
#include "app/study/visitor_study.hpp"
#include "core/scene_layout.hpp"
#include "core/study/protocol_loader.hpp"
#include "render/scene_view.hpp"
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

//! A bar's box on a width×height screen as `scene` is shown there, with a letter's height
//! of margin below its near end (where its sign hangs: render::draw_bar_signs).
render::PixelRect bar_on_screen(const Scene& scene, int id, int width, int height) {
  const Target& t = scene.targets.at(static_cast<std::size_t>(id));
  render::Box box;
  box.add({t.x_min, t.top_y - t.thickness_m, -t.length_m / 2});
  box.add({t.x_max, t.top_y, t.length_m / 2});
  render::PixelRect r = render::screen_rect(render::view_projection(scene, double(width) / height), width, height, box);
  r.y1 = std::min(height, r.y1 + height / 12);
  return r;
}

TEST(VisitorStudy, TheConsentsAnswersNeverSitWhereTheOffersYesWasAndAreLaidOutForTheScreensShape) {
  // A visitor strikes the offer's "Yes" (the kiosk's last bar) and strikes again at the same
  // place, as one does on a xylophone: in portrait the consent's "No" sat right there and
  // declined at once (issue 48, item 1). Each answer bar of the consent, with its sign, stays
  // clear of the offer's "Yes" bar and its sign at every shape; on a portrait screen the
  // study's bars stand close together across the screen's width, shown larger than in the
  // landscape band (stacked, as the instruments are, they were thin sticks).
  const Scene& base = test::percussion();
  const study::StudyProtocol protocol = study::load_study_protocol(test::config_dir() / "study" / "visitor.toml",
                                                                   base.materials, base.targets.size());
  for (const auto& [w, h] : {std::pair{1920, 1080}, std::pair{1280, 1024}, std::pair{1080, 1920}, std::pair{2560, 1080}}) {
    const double aspect = double(w) / h;
    const std::string shape = std::to_string(w) + "x" + std::to_string(h);
    const Scene kiosk = laid_out(base, layout_for(base, aspect));
    // The offer's "Yes" bar and the column above it: a strike comes down from above, so a
    // bar anywhere on that way is struck by a visitor striking "Yes" again.
    render::PixelRect yes = bar_on_screen(kiosk, static_cast<int>(kiosk.targets.size()) - 1, w, h);
    yes.y0 = 0;
    for (const bool rtl : {false, true}) {  // and in Arabic or Hebrew, "Yes" read first: on the right
      const Scene mirrored = study_scene_for(base, protocol, aspect, rtl);
      EXPECT_EQ(mirrored.layout, kiosk.layout) << shape;
      const std::vector<AnswerBar> answers = answer_bars(mirrored, protocol);
      ASSERT_GE(answers.size(), 2u);
      for (std::size_t k = 0; k < 2; ++k) {
        const render::PixelRect answer = bar_on_screen(mirrored, answers[k].target, w, h);
        EXPECT_FALSE(render::overlap(yes, answer))
            << shape << (rtl ? " right to left" : "") << ": the consent's " << (k == 0 ? "Yes" : "No") << " bar ("
            << answer.x0 << "," << answer.y0 << ")-(" << answer.x1 << "," << answer.y1 << ") under the offer's Yes ("
            << yes.x0 << "," << yes.y0 << ")-(" << yes.x1 << "," << yes.y1 << ")";
      }
      const int first = bar_on_screen(mirrored, answers[0].target, w, h).x0;
      const int second = bar_on_screen(mirrored, answers[1].target, w, h).x0;
      EXPECT_EQ(first > second, rtl) << shape << ": the first answer is the first read";
    }
    const Scene study = study_scene_for(base, protocol, aspect);
    const std::vector<AnswerBar> bars = answer_bars(study, protocol);
    if (h > w) {  // each bar wider on the screen than in the landscape band
      const render::PixelRect stacked = bar_on_screen(study, bars[0].target, w, h);
      const Scene landscape = make_study_scene(base, protocol);
      const render::PixelRect band = bar_on_screen(landscape, bars[0].target, w, h);
      // What the walkthrough met: the landscape band's "No" on the way down to "Yes".
      EXPECT_TRUE(render::overlap(yes, bar_on_screen(landscape, bars[1].target, w, h))) << shape;
      EXPECT_EQ(study.layout, SceneLayout::portrait);
      EXPECT_GT(stacked.x1 - stacked.x0, 1.2 * (band.x1 - band.x0)) << shape;
    }
  }
}

}  // namespace
}  // namespace mallet::app
