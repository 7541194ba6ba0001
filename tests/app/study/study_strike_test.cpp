// Answers by striking (response = "strike"): the study scene's answer bars, a hand that can
// strike them but not the stimulus bars, and a headless session whose scripted answers are
// struck through the strike route: rows say source=strike, their response times are the
// contacts the route found, and an answer strike clicks on the speaker and leaves the
// actuator silent.
#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "core/strike_loop.hpp"
#include "app/study/study_session.hpp"
#include "app/study/study_stimuli.hpp"
#include "audio/wav_file.hpp"
#include "core/app_config.hpp"
#include "core/ghost_player.hpp"
#include "core/study/results_csv.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

std::string strike_protocol(const std::string& task_lines, const std::string& answer_strike = "") {
  return "name = \"strike\"\n" + task_lines +
         "conditions = [\"both\", \"none\"]\nrepetitions = 2\nseed = 3\noutput = \"s.csv\"\n"
         "impact_speed_m_per_s = 0.5\nsound = false\nreference_bar = 0\nresponse = \"strike\"\n" +
         answer_strike +
         "[timing]\nlead_s = 0.1\nstimulus_s = 0.2\nstimulus_interval_s = 0.3\ninter_trial_s = 0.1\n"
         "[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n"
         "[[stimulus]]\nname = \"metal\"\nmaterial = \"metal\"\n";
}

const std::string k2afc = "task = \"2afc_harder\"\n";
const std::string kPair = "[[pair]]\na = \"wood\"\nb = \"metal\"\n";

StudyOptions options(const fs::path& dir, const std::string& protocol) {
  std::ofstream(dir / "p.toml") << protocol;
  StudyOptions o;
  o.protocol = dir / "p.toml";
  o.participant = "P3";
  o.out = dir / "r.csv";
  o.scene = test::percussion_scene();
  return o;
}

TEST(StudyStrike, TheSceneHasOneAnswerBarPerChoiceApartFromTheStimulusBar) {
  const fs::path dir = test::scratch_dir();
  for (const std::string& task : {k2afc, std::string("task = \"name_material\"\n")}) {
    const StudyPlan plan = plan_study(options(dir, strike_protocol(task) + (task == k2afc ? kPair : "")));
    const Scene scene = make_study_scene(plan.base, plan.protocol);
    const std::vector<AnswerBar> bars = answer_bars(scene, plan.protocol);
    const std::vector<std::string> choices = plan.protocol.answer_choices();
    ASSERT_EQ(bars.size(), choices.size());
    const Target& stimulus = scene.targets.at(0);
    const double gap = 2 * scene.mallet_radius_m;  // contact zones of bars further apart never meet
    for (std::size_t k = 0; k < bars.size(); ++k) {
      EXPECT_EQ(bars[k].answer, choices[k]);
      const Target& bar = scene.targets.at(static_cast<std::size_t>(bars[k].target));
      EXPECT_TRUE(bar.hand_strikes);
      EXPECT_GT(std::max(bar.x_min - stimulus.x_max, stimulus.x_min - bar.x_max), gap) << k;
      if (k > 0) {
        EXPECT_GT(bar.x_min - scene.targets.at(static_cast<std::size_t>(bars[k - 1].target)).x_max, gap);
      }
      // On screen: within the scene's picture.
      EXPECT_GE(bar.x_min, std::min(plan.base.screen_to_world.left_m, plan.base.screen_to_world.right_m));
      EXPECT_LE(bar.x_max, std::max(plan.base.screen_to_world.left_m, plan.base.screen_to_world.right_m));
    }
    for (const Target& t : scene.targets)
      if (std::none_of(bars.begin(), bars.end(), [&](const AnswerBar& b) { return b.target == t.id; })) {
        EXPECT_FALSE(t.hand_strikes) << t.id;
      }
    // sound = false: the stimuli's instrument is silent, the answer bars click. Each bar
    // rests on the rails made for its kind (metal on the glockenspiel's, wood on the xylophone's).
    for (const Instrument& inst : scene.instruments) {
      if (!inst.targets.empty()) {
        EXPECT_EQ(inst.speaker, inst.voice == "click") << inst.name;
        EXPECT_EQ(inst.rail_model, inst.bar_model == "metal_bar.glb" ? "glockenspiel_rail.glb" : "xylophone_rail.glb")
            << inst.name << ": " << inst.bar_model;
      }
    }
  }
}

TEST(StudyStrike, AHandStrikesTheAnswerBarsButOnlyRestsOnTheStimulusBar) {
  const fs::path dir = test::scratch_dir();
  const StudyPlan plan = plan_study(options(dir, strike_protocol(k2afc) + kPair));
  const Scene scene = make_study_scene(plan.base, plan.protocol);
  const std::vector<AnswerBar> bars = answer_bars(scene, plan.protocol);
  StrikeLoop loop(scene, plan.config);
  const GhostPath path = ghost_player(
      scene, {{0, 200'000'000, 0.5}, {bars[0].target, 900'000'000, 0.5}, {bars[1].target, 1'600'000'000, 0.5}}, 1000);
  std::vector<Impact> impacts;
  for (const PointerSample& s : path.samples)
    if (auto i = loop.feed(s.t_ns, {s.x, s.y})) impacts.push_back(*i);
  ASSERT_EQ(impacts.size(), 2u) << "the stimulus bar is not struck by the hand";
  EXPECT_EQ(impacts[0].target, bars[0].target);
  EXPECT_EQ(impacts[0].t_ns, path.contacts[1]);
  EXPECT_EQ(impacts[1].target, bars[1].target);
}

TEST(StudyStrike, ScriptedAnswersAreStruckAndTimedByTheirContact) {
  const fs::path dir = test::scratch_dir();
  StudyOptions o = options(dir, strike_protocol(k2afc) + kPair);
  // The second answer asks for 20 ms: faster than a stroke's descent from hover height
  // (0.08 m at 0.5 m/s = 160 ms), so its contact, and its response time, come later.
  std::ofstream(dir / "answers.txt") << "1 500\n2 20\n1 612.5\n2 700\n";
  o.answers = dir / "answers.txt";
  o.audio = dir / "a.wav";
  const StudyRunResult r = run_study(o);
  ASSERT_EQ(r.answered, 4);
  EXPECT_EQ(r.source, "strike");
  const std::vector<study::ResultRow> rows = study::read_results(dir / "r.csv").rows;
  ASSERT_EQ(rows.size(), 4u);
  const char* answers[] = {"1", "2", "1", "2"};
  const double times[] = {500.0, 160.0, 612.5, 700.0};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].source, "strike");
    EXPECT_EQ(rows[i].answer, answers[i]);
    EXPECT_NEAR(rows[i].response_time_ms, times[i], 1e-3) << i;
  }

  // The speaker: silent stimuli (sound = false), a click at each answer's contact; the
  // actuator: nothing at an answer strike (feel = none). Contacts on the simulated clock
  // from 0: each trial's answer window opens 0.6 s after its start (lead 0.1 + interval
  // 0.3 + stimulus 0.2), the next trial starts 0.1 s after the answer.
  const audio::WavData wav = audio::read_wav(dir / "a.wav");
  const std::vector<double> speaker = wav.channel(plan_study(o).config.audio.routing.acoustic);
  const std::vector<double> actuator = wav.channel(plan_study(o).config.audio.routing.actuator);
  const double rate = wav.sample_rate_hz;
  std::vector<std::size_t> contacts;
  double start = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double contact = start + 0.6 + rows[i].response_time_ms / 1e3;
    contacts.push_back(static_cast<std::size_t>(std::ceil(contact * rate)));
    start = contact + 0.1;
  }
  std::size_t sounding = 0;
  for (std::size_t n = 0; n < speaker.size(); ++n) {
    if (speaker[n] == 0.0) continue;
    ++sounding;
    const bool after_a_contact = std::any_of(contacts.begin(), contacts.end(), [&](std::size_t c) {
      return n >= c && n < c + static_cast<std::size_t>(0.1 * rate);
    });
    ASSERT_TRUE(after_a_contact) << "the speaker sounds at " << static_cast<double>(n) / rate << " s";
  }
  EXPECT_GT(sounding, contacts.size() * static_cast<std::size_t>(0.005 * rate)) << "each answer clicks";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_NE(speaker.at(contacts[i] + 1), 0.0) << "answer " << i << " clicks from its contact";
    if (rows[i].condition != "none") continue;  // "both": the stimuli still ring on the actuator
    for (std::size_t n = contacts[i]; n < contacts[i] + static_cast<std::size_t>(0.1 * rate); ++n)
      ASSERT_EQ(actuator.at(n), 0.0) << "answer " << i;
  }
}

TEST(StudyStrike, AVoiceTheSceneLacksIsReportedWhereTheProtocolNamesIt) {
  const fs::path dir = test::scratch_dir();
  try {
    plan_study(options(dir, strike_protocol(k2afc, "[answer_strike]\nsound = \"gong\"\n") + kPair));
    FAIL() << "no error";
  } catch (const FileError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind((dir / "p.toml").string() + ":12:9: answer_strike.sound: no voice \"gong\" in ", 0), 0u)
        << what;
    EXPECT_NE(what.find("(known: xylophone, glockenspiel"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace mallet::app
