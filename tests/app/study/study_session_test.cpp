// The trial logic shared by the headless and the windowed study (present → answer → row),
// driven by a scripted stage and answer source: no window, no device, no wall clock.
#include <fstream>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "app/study/study_session.hpp"
#include "app/study/study_stimuli.hpp"
#include "core/study/results_csv.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;
constexpr Nanos kMs = 1'000'000;

//! 2 trials of 2 taps: lead 100 ms, taps 200 ms, 300 ms apart.
fs::path tiny_protocol(const fs::path& dir) {
  const fs::path p = dir / "tiny.toml";
  std::ofstream(p) << "name = \"tiny\"\ntask = \"2afc_harder\"\nconditions = [\"both\"]\nrepetitions = 2\nseed = 1\n"
                      "output = \"tiny.csv\"\nimpact_speed_m_per_s = 0.5\nsound = false\nreference_bar = 0\n"
                      "[timing]\nlead_s = 0.1\nstimulus_s = 0.2\nstimulus_interval_s = 0.3\ninter_trial_s = 0.1\n"
                      "[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n"
                      "[[stimulus]]\nname = \"wood_B130\"\nmaterial = \"wood\"\ndecay_scale = 1.30\n"
                      "[[pair]]\na = \"wood\"\nb = \"wood_B130\"\n";
  return p;
}

StudyOptions options(const fs::path& dir) {
  StudyOptions o;
  o.protocol = tiny_protocol(dir);
  o.participant = "P7";
  o.out = dir / "r.csv";
  o.scene = test::percussion_scene();
  return o;
}

//! A clock that jumps where it is asked to; records the taps.
class FakeStage final : public StudyStage {
 public:
  Nanos now() override { return t; }
  bool wait_until(Nanos until) override {
    t = std::max(t, until);
    return true;
  }
  //! Each tap heard 2 ms and shown 20 ms after its contact, the second 5 ms later still.
  Strike present(const Impact& impact) override {
    EXPECT_EQ(impact.t_ns, t) << "a tap is presented when it is due";
    taps.push_back(impact);
    const Nanos later = taps.size() % 2 == 0 ? 5 * kMs : 0;
    Strike s;
    s.impact = impact;
    s.heard_ns = impact.t_ns + 2 * kMs + later;
    s.shown_ns = impact.t_ns + 20 * kMs + later;
    s.stimulus = true;
    return s;
  }
  double visual_offset_m(Nanos) const override { return taps.empty() ? 0.0 : 0.002; }
  double take_actuator_peak() override { return std::exchange(peak, 0.0) + (taps.empty() ? 0.0 : 0.25); }
  std::optional<Strike> hand(Nanos, Vec2) override { return std::nullopt; }
  Exploration explore(const Scene&, Nanos) override { return {}; }
  std::optional<ActuatorEq> actuator_eq() const override { return eq; }
  Nanos t = 5 * kNanosPerSecond;  // not 0: the real clock is not
  std::optional<ActuatorEq> eq;  //!< the calibration the stage says its engine applies
  double peak = 0;
  std::vector<Impact> taps;
};

//! Answers given at a fixed delay after the window opens; nothing once the list ends.
class ListAnswers final : public AnswerSource {
 public:
  explicit ListAnswers(std::vector<std::pair<std::string, Nanos>> a) : list(std::move(a)) {}
  std::optional<TrialAnswer> answer(const study::ScheduledTrial&, Nanos opens) override {
    ++asked;
    if (next == list.size()) return std::nullopt;  // the participant pressed Esc
    const auto& [answer, delay] = list[next++];
    return TrialAnswer{answer, opens + delay};
  }
  std::string name() const override { return "keys"; }
  std::vector<std::pair<std::string, Nanos>> list;
  std::size_t next = 0;
  int asked = 0;
};

TEST(StudySession, OneTrialPresentsBothTapsThenTakesTheAnswerAsARow) {
  const fs::path dir = test::scratch_dir();
  const StudyPlan plan = plan_study(options(dir));
  ASSERT_EQ(plan.schedule.size(), 2u);
  const Scene scene = make_study_scene(plan.base, plan.protocol);
  FakeStage stage;
  ListAnswers answers({{"2", 640 * kMs}});
  Nanos next = 0;
  const Nanos start = stage.t;
  const std::optional<study::ResultRow> row =
      run_trial(plan, scene, plan.schedule[0], stage, answers, start, "S", next);
  ASSERT_TRUE(row);
  ASSERT_EQ(stage.taps.size(), 2u);
  EXPECT_EQ(stage.taps[0].t_ns, start + 100 * kMs);
  EXPECT_EQ(stage.taps[1].t_ns, start + 400 * kMs);
  EXPECT_EQ(row->trial, 1);
  EXPECT_EQ(row->participant, "P7");
  EXPECT_EQ(row->answer, "2");
  EXPECT_EQ(row->source, "keys");
  EXPECT_DOUBLE_EQ(row->response_time_ms, 640.0);  // from the end of the second tap
  EXPECT_DOUBLE_EQ(row->visual_peak_m, 0.002);
  EXPECT_DOUBLE_EQ(row->actuator_peak, 0.25);
  // The cues' onsets the strike route gave, after each tap's contact: the trial's latest.
  EXPECT_DOUBLE_EQ(row->actuator_onset_ms, 7.0);
  EXPECT_DOUBLE_EQ(row->picture_onset_ms, 25.0);
  EXPECT_EQ(next, start + 600 * kMs + 640 * kMs + 100 * kMs);
}

TEST(StudySession, EachRowNamesTheActuatorCalibrationTheStagesEngineApplies) {
  const fs::path dir = test::scratch_dir();
  const StudyPlan plan = plan_study(options(dir));
  const Scene scene = make_study_scene(plan.base, plan.protocol);
  FakeStage stage;
  ActuatorEq eq;
  eq.created_utc = "2026-12-06T09:30:00Z";
  eq.sample_rate_hz = 48000;
  eq.taps = std::vector<double>(16, 0.25);
  stage.eq = eq;
  ListAnswers answers({{"1", 300 * kMs}, {"2", 300 * kMs}});
  EXPECT_EQ(run_session(plan, scene, stage, answers).answered, 2);
  const std::vector<study::ResultRow> rows = study::read_results(dir / "r.csv").rows;
  ASSERT_EQ(rows.size(), 2u);
  for (const study::ResultRow& r : rows) {
    EXPECT_EQ(r.actuator_eq_hash, eq.hash());
    EXPECT_EQ(r.actuator_eq_utc, "2026-12-06T09:30:00Z");
  }
}

TEST(StudySession, AKeyFromBeforeTheWindowOpenedCountsAsAtItsOpening) {
  const fs::path dir = test::scratch_dir();
  const StudyPlan plan = plan_study(options(dir));
  const Scene scene = make_study_scene(plan.base, plan.protocol);
  FakeStage stage;
  ListAnswers answers({{"1", -50 * kMs}});
  Nanos next = 0;
  const auto row = run_trial(plan, scene, plan.schedule[0], stage, answers, stage.t, "S", next);
  ASSERT_TRUE(row);
  EXPECT_DOUBLE_EQ(row->response_time_ms, 0.0);
}

TEST(StudySession, QuittingKeepsTheAnsweredRowsAndTheSameCallResumes) {
  const fs::path dir = test::scratch_dir();
  const StudyOptions o = options(dir);
  {
    const StudyPlan plan = plan_study(o);
    const Scene scene = make_study_scene(plan.base, plan.protocol);
    FakeStage stage;
    ListAnswers answers({{"1", 300 * kMs}});  // then Esc
    const StudyRunResult r = run_session(plan, scene, stage, answers);
    EXPECT_EQ(r.answered, 1);
    EXPECT_TRUE(r.stopped);
    EXPECT_EQ(answers.asked, 2);
  }
  const study::ResultsFile after_quit = study::read_results(dir / "r.csv");
  ASSERT_EQ(after_quit.rows.size(), 1u);
  EXPECT_TRUE(after_quit.warnings.empty());
  {
    const StudyPlan plan = plan_study(o);
    EXPECT_EQ(plan.done, (std::set<int>{1}));
    const Scene scene = make_study_scene(plan.base, plan.protocol);
    FakeStage stage;
    ListAnswers answers({{"2", 500 * kMs}});
    const StudyRunResult r = run_session(plan, scene, stage, answers);
    EXPECT_EQ(r.already_recorded, 1);
    EXPECT_EQ(r.answered, 1);
    EXPECT_FALSE(r.stopped);
    EXPECT_EQ(stage.taps.size(), 2u) << "only the remaining trial is presented";
  }
  const std::vector<study::ResultRow> rows = study::read_results(dir / "r.csv").rows;
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].trial, 1);
  EXPECT_EQ(rows[1].trial, 2);
  EXPECT_EQ(rows[1].answer, "2");
  EXPECT_DOUBLE_EQ(rows[1].response_time_ms, 500.0);
}

TEST(StudySession, TheKeysAndThePromptComeFromTheProtocol) {
  const fs::path dir = test::scratch_dir();
  StudyOptions o = options(dir);
  const StudyPlan harder = plan_study(o);
  EXPECT_EQ(answer_prompt(harder.protocol), "Which tap felt harder? Press 1 or 2");
  ASSERT_EQ(answer_keys(harder.protocol).size(), 2u);
  EXPECT_EQ(answer_keys(harder.protocol)[1].key, '2');

  o.protocol = test::config_dir() / "study" / "name_material.toml";
  const StudyPlan named = plan_study(o);
  const std::vector<AnswerKey> keys = answer_keys(named.protocol);
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].key, 'W');
  EXPECT_EQ(keys[0].answer, "wood");
  EXPECT_EQ(keys[1].key, 'M');
  EXPECT_EQ(answer_prompt(named.protocol), "Which material? W wood, M metal");

  // Two materials with the same first letter: the digits.
  study::StudyProtocol clash = named.protocol;
  clash.stimuli[1].material.name = "walnut";
  const std::vector<AnswerKey> digits = answer_keys(clash);
  ASSERT_EQ(digits.size(), 2u);
  EXPECT_EQ(digits[0].key, '1');
  EXPECT_EQ(digits[1].key, '2');
  EXPECT_EQ(answer_prompt(clash), "Which material? 1 wood, 2 walnut");
}

}  // namespace
}  // namespace mallet::app
