// Study protocols: the shipped examples load; every mistake is one FILE:LINE:COL line.
#include <cmath>

#include <gtest/gtest.h>

#include "core/study/protocol_loader.hpp"
#include "core/visitor_language.hpp"
#include "core/study/study_fixture.hpp"

namespace mallet::study {
namespace {

StudyProtocol load_shipped(const char* file) {
  return load_study_protocol(test::config_dir() / "study" / file, test::percussion().materials,
                             test::percussion().targets.size());
}

TEST(StudyProtocol, ShippedExampleLoads) {
  const StudyProtocol p = load_shipped("example.toml");
  EXPECT_EQ(p.name, "harder-2afc-example");
  EXPECT_EQ(p.task, StudyTask::two_afc_harder);
  EXPECT_EQ(p.conditions.size(), 4u);
  ASSERT_EQ(p.stimuli.size(), 5u);
  EXPECT_DOUBLE_EQ(p.stimuli[3].material.visual.decay_per_s, 8.0 * 1.3);
  EXPECT_DOUBLE_EQ(p.stimuli[3].material.actuator.decay_per_s, 80.0 * 1.3);
  EXPECT_EQ(p.stimuli[3].material.visual.freq_hz, 5.0);  // only B is scaled
  ASSERT_EQ(p.pairs.size(), 4u);
  EXPECT_NEAR(p.pairs[0].difference_pct, 5.0, 1e-9);
  EXPECT_NEAR(p.pairs[3].difference_pct, 12.5, 1e-9);
  EXPECT_EQ(p.items() * p.conditions.size() * static_cast<std::size_t>(p.repetitions), 32u);
  EXPECT_EQ(p.timing.stimulus_interval, 1'200'000'000);
  EXPECT_FALSE(p.sound);
}

TEST(StudyProtocol, ShippedNameMaterialLoads) {
  const StudyProtocol p = load_shipped("name_material.toml");
  EXPECT_EQ(p.task, StudyTask::name_material);
  EXPECT_EQ(p.named.size(), 2u);
  EXPECT_EQ(p.answer_choices(), (std::vector<std::string>{"wood", "metal"}));
}

std::string error_of(const std::string& text) {
  return test::file_error_of([&] { test::parse_protocol(text, "bad.toml"); }).what();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(StudyProtocol, MistakesNameFileLineColumnAndKey) {
  const std::string ok = test::kTwoAfcProtocol;
  EXPECT_EQ(error_of(replaced(ok, "material = \"metal\"", "material = \"glass\"")),
            "bad.toml:16:12: stimulus[2].material: unknown material \"glass\" (the scene has: wood, metal)");
  EXPECT_EQ(error_of(replaced(ok, "repetitions = 4", "repetitions = 3")),
            "bad.toml:5:15: repetitions: must be even for 2afc_harder and steeper, so each pair is shown in both "
            "orders equally often");
  EXPECT_EQ(error_of(replaced(ok, "\"none\"]", "\"smell\"]")),
            "bad.toml:4:14: conditions: unknown condition \"smell\" (visual_only, tactile_only, both, none)");
  EXPECT_EQ(error_of(replaced(ok, "seed = 42", "seed = 42\nrepetitons = 2")),
            "bad.toml:7:14: repetitons: unknown key (misspelt? see the comments in the shipped file)");
  EXPECT_EQ(error_of(replaced(ok, "b = \"wood_B110\"", "b = \"wood_B999\"")),
            "bad.toml:19:5: pair[0].b: no [[stimulus]] named \"wood_B999\" (known: wood, wood_B110, metal)");
  EXPECT_EQ(error_of(replaced(ok, "decay_scale = 1.1", "decay_scale = 1.0")),
            "bad.toml:19:5: pair[0].b: \"harder\" is the stimulus with the larger decay_per_s (B), visual and "
            "actuator alike; these two are equal or ordered differently by the two triples");
  EXPECT_EQ(error_of(replaced(ok, "task = \"2afc_harder\"", "task = \"3afc\"")),
            "bad.toml:3:8: task: expected \"2afc_harder\", \"name_material\" or \"texture_slope\", got \"3afc\"");
  EXPECT_EQ(error_of(replaced(ok, "name = \"t\"", "name = \"a,b\"")),
            "bad.toml:2:8: name: \"a,b\" must be 1-64 letters, digits, '_', '-' or '.'");
  EXPECT_EQ(error_of("name = \"t\"\ntask = \n"), "bad.toml:2:8: Error while parsing key-value pair: expected value, saw '\\n'");
}

TEST(StudyProtocol, ShippedAdaptiveProtocolsLoadWithTheirGridOfPairs) {
  const StudyProtocol s = load_shipped("staircase.toml");
  EXPECT_EQ(s.procedure, StudyProcedure::staircase);
  EXPECT_EQ(s.adaptive.staircase.down, 2);
  EXPECT_EQ(s.adaptive.staircase.steps, (std::vector<double>{8, 4, 2}));
  EXPECT_EQ(s.adaptive.staircase.min, 0.5);
  // One pair per 0.5 % from 0.5 to 60: the reference against itself made harder.
  ASSERT_EQ(s.pairs.size(), 120u);
  EXPECT_EQ(s.pairs[0].difference_pct, 0.5);
  EXPECT_EQ(s.pairs[119].difference_pct, 60.0);
  const Stimulus& hardest = s.stimuli.at(static_cast<std::size_t>(s.pairs[119].b));
  EXPECT_EQ(hardest.name, "wood+60");
  EXPECT_DOUBLE_EQ(hardest.material.actuator.decay_per_s, 80.0 * 1.6);
  EXPECT_EQ(s.pairs[119].harder, s.pairs[119].b);
  const StudyProtocol q = load_shipped("quest.toml");
  EXPECT_EQ(q.procedure, StudyProcedure::quest);
  EXPECT_EQ(q.adaptive.quest_model.shape, QuestShape::weibull);
  EXPECT_EQ(q.adaptive.quest_trials, 40);
  EXPECT_EQ(q.adaptive.quest_prior.mean, 20);
}

TEST(StudyProtocol, AnAdaptiveProtocolsMistakesAreOneLineEach) {
  const std::string ok =
      "name = \"s\"\ntask = \"2afc_harder\"\nprocedure = \"staircase\"\nconditions = [\"both\"]\nseed = 1\n"
      "reference = \"wood\"\n[staircase]\nsteps_pct = [8, 4]\n[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n";
  EXPECT_NO_THROW(test::parse_protocol(ok, "a.toml"));
  EXPECT_EQ(error_of(replaced(ok, "steps_pct = [8, 4]", "steps_pct = [8, 3.3]")),
            "bad.toml:8:13: staircase.steps_pct: each step must be a positive multiple of 0.5 % (the grid of stimuli)");
  EXPECT_EQ(error_of(replaced(ok, "seed = 1", "seed = 1\nrepetitions = 2")),
            "bad.toml:6:15: repetitions: an adaptive protocol's trials end by its own stop rule ([staircase]); "
            "remove it");
  EXPECT_EQ(error_of(replaced(ok, "\"staircase\"\nconditions", "\"bisection\"\nconditions")),
            "bad.toml:3:13: procedure: expected \"constant\", \"staircase\", \"quest\" or \"quest_plus\", got "
            "\"bisection\"");
  EXPECT_EQ(error_of(replaced(ok, "reference = \"wood\"", "reference = \"oak\"")),
            "bad.toml:6:13: reference: no [[stimulus]] named \"oak\" (known: wood)");
}

TEST(StudyProtocol, ShippedQuestPlusLoadsItsGrid) {
  const StudyProtocol q = load_shipped("quest_plus.toml");
  EXPECT_EQ(q.procedure, StudyProcedure::quest_plus);
  const QuestPlusSetup& s = q.adaptive.quest_plus;
  EXPECT_EQ(s.model.shape, PsychometricShape::logistic);
  EXPECT_EQ(s.model.guess, 0.5);
  EXPECT_EQ(s.model.criterion, 0.75);
  ASSERT_EQ(s.grid.thresholds.size(), 40u);  // { lo = 1, hi = 40, points = 40 }
  EXPECT_EQ(s.grid.thresholds.front(), 1);
  EXPECT_EQ(s.grid.thresholds[11], 12);
  EXPECT_EQ(s.grid.thresholds.back(), 40);
  EXPECT_EQ(s.grid.slopes, (std::vector<double>{0.05, 0.1, 0.2, 0.4}));
  EXPECT_EQ(s.grid.lapses, (std::vector<double>{0, 0.02, 0.04}));
  EXPECT_FALSE(s.threshold_prior);
  EXPECT_EQ(q.adaptive.quest_plus_trials, 64);
  ASSERT_EQ(q.pairs.size(), 120u);  // the stimuli: 0.5 … 60 %
  EXPECT_EQ(q.pairs.back().difference_pct, 60.0);
}

TEST(StudyProtocol, QuestPlusDefaultsAndAListOfThresholds) {
  const std::string base =
      "name = \"q\"\ntask = \"2afc_harder\"\nprocedure = \"quest_plus\"\nconditions = [\"both\"]\nseed = 1\n"
      "reference = \"wood\"\n[quest_plus]\nslope = [0.25]\n[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n";
  const StudyProtocol d = test::parse_protocol(base, "a.toml");
  const QuestPlusSetup& s = d.adaptive.quest_plus;
  // Without threshold_pct the thresholds are the tested differences; lapses known at 2 %.
  ASSERT_EQ(s.grid.thresholds.size(), 120u);
  EXPECT_EQ(s.grid.thresholds[0], 0.5);
  EXPECT_EQ(s.grid.thresholds[119], 60);
  EXPECT_EQ(s.grid.lapses, (std::vector<double>{0.02}));
  EXPECT_EQ(d.adaptive.quest_plus_trials, 64);
  const StudyProtocol listed = test::parse_protocol(
      replaced(base, "slope = [0.25]",
               "slope = [3.5]\nshape = \"weibull\"\ncriterion = 0.8\nthreshold_pct = [5, 10, 20]\nprior = "
               "\"gaussian\"\nprior_mean_pct = 10\nprior_sd_pct = 5\ntrials = 30"),
      "a.toml");
  const QuestPlusSetup& l = listed.adaptive.quest_plus;
  EXPECT_EQ(l.model.shape, PsychometricShape::weibull);
  EXPECT_EQ(l.model.criterion, 0.8);
  EXPECT_EQ(l.grid.thresholds, (std::vector<double>{5, 10, 20}));
  ASSERT_TRUE(l.threshold_prior);
  EXPECT_EQ(l.threshold_prior->mean, 10);
  EXPECT_EQ(l.threshold_prior->sd, 5);
  EXPECT_EQ(listed.adaptive.quest_plus_trials, 30);
}

TEST(StudyProtocol, AQuestPlusProtocolsMistakesAreOneLineEach) {
  const std::string ok =
      "name = \"q\"\ntask = \"2afc_harder\"\nprocedure = \"quest_plus\"\nconditions = [\"both\"]\nseed = 1\n"
      "reference = \"wood\"\n[quest_plus]\nslope = [0.1, 0.2]\nlapse = [0, 0.02]\n"
      "threshold_pct = { lo = 1, hi = 40, points = 40 }\n[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n";
  EXPECT_NO_THROW(test::parse_protocol(ok, "a.toml"));
  EXPECT_EQ(error_of(replaced(ok, "slope = [0.1, 0.2]", "slope = [0.2, 0.1]")),
            "bad.toml:8:9: quest_plus.slope: must increase (0.2 then 0.1)");
  EXPECT_EQ(error_of(replaced(ok, "slope = [0.1, 0.2]", "slope = []")), "bad.toml:8:9: quest_plus.slope: lists no value");
  EXPECT_EQ(error_of(replaced(ok, "slope = [0.1, 0.2]\n", "")), "bad.toml:7:1: quest_plus.slope: missing (required)");
  EXPECT_EQ(error_of(replaced(ok, "lapse = [0, 0.02]", "lapse = [0, 0.5]")),
            "bad.toml:9:9: quest_plus.lapse: each must be in [0, 0.2], got 0.5");
  EXPECT_EQ(error_of(replaced(ok, "points = 40", "points = 1")),
            "bad.toml:10:45: quest_plus.threshold_pct.points: must be in [2, 1000], got 1");
  EXPECT_EQ(error_of(replaced(ok, "hi = 40", "hi = 0.5")),
            "bad.toml:10:32: quest_plus.threshold_pct.hi: must be > lo (1) and <= 100, got 0.5");
  EXPECT_EQ(error_of(replaced(ok, "lo = 1,", "lo = 1, step = 2,")),
            "bad.toml:10:34: quest_plus.threshold_pct.step: unknown key (misspelt? see the comments in the shipped "
            "file)");
  EXPECT_EQ(error_of(replaced(ok, "{ lo = 1, hi = 40, points = 40 }", "[1, 40, 0]")),
            "bad.toml:10:17: quest_plus.threshold_pct: each must be in [0.01, 100], got 0");
  EXPECT_EQ(error_of(replaced(ok, "[quest_plus]", "[quest_plus]\ncriterion = 0.5")),
            "bad.toml:8:13: quest_plus.criterion: must lie between the 2AFC guess rate 0.5 and 1 (both excluded), "
            "got 0.5");
  EXPECT_EQ(error_of(replaced(ok, "[quest_plus]", "[quest_plus]\nshape = \"probit\"")),
            "bad.toml:8:9: quest_plus.shape: expected \"logistic\", \"weibull\", \"normal\" or \"gumbel\", got "
            "\"probit\"");
  EXPECT_EQ(error_of(replaced(ok, "[quest_plus]", "[quest_plus]\nprior_sd_pct = 5")),
            "bad.toml:8:16: quest_plus.prior_sd_pct: only prior = \"gaussian\" uses it");
  EXPECT_EQ(error_of(replaced(ok, "[quest_plus]", "[quest_plus]\nprior = \"gaussian\"\nprior_mean_pct = 10")),
            "bad.toml:7:1: quest_plus.prior_sd_pct: missing (required)");
  EXPECT_EQ(error_of(replaced(replaced(ok, "points = 40", "points = 1000"), "lapse = [0, 0.02]",
                              "lapse = [0, 0.01, 0.02, 0.03, 0.04]")),
            "bad.toml:10:17: quest_plus.threshold_pct: 1000 thresholds × 2 slopes × 5 lapses × 120 stimuli make "
            "1.2e+06 likelihoods, more than QUEST+ tables (1e+06): fewer points, or a narrower min_pct-max_pct");
  EXPECT_EQ(error_of(replaced(ok, "[quest_plus]", "[quest]")),
            "bad.toml:1:1: quest_plus: missing (required)");
}

TEST(StudyProtocol, TheShippedAdaptiveProtocolsKeepTodaysDefaults) {
  const StudyProtocol s = load_shipped("staircase.toml");
  EXPECT_EQ(s.adaptive.staircase.step_type, StaircaseStepType::linear);
  EXPECT_FALSE(s.adaptive.staircase.initial_one_up_one_down);
  EXPECT_EQ(s.adaptive.staircase.discard_reversals, 0);
  const StudyProtocol q = load_shipped("quest.toml");
  EXPECT_EQ(q.adaptive.quest_model.scale, QuestScale::linear);
  EXPECT_EQ(q.adaptive.quest_model.placement, QuestPlacement::mean);
  EXPECT_EQ(q.adaptive.quest_prior.sd, 15);
}

const std::string kStaircase =
    "name = \"s\"\ntask = \"2afc_harder\"\nprocedure = \"staircase\"\nconditions = [\"both\"]\nseed = 1\n"
    "reference = \"wood\"\n[staircase]\nsteps_pct = [8, 4]\n[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n";

TEST(StudyProtocol, StaircaseStepTypesTheInitialPhaseAndDiscardedReversals) {
  const StudyProtocol db = test::parse_protocol(
      replaced(kStaircase, "steps_pct = [8, 4]",
               "step_type = \"db\"\nsteps_db = [4, 2, 1]\ninitial_one_up_one_down = true\ndiscard_reversals = 2"),
      "a.toml");
  EXPECT_EQ(db.adaptive.staircase.step_type, StaircaseStepType::db);
  EXPECT_EQ(db.adaptive.staircase.steps, (std::vector<double>{4, 2, 1}));
  EXPECT_TRUE(db.adaptive.staircase.initial_one_up_one_down);
  EXPECT_EQ(db.adaptive.staircase.discard_reversals, 2);
  const StudyProtocol log =
      test::parse_protocol(replaced(kStaircase, "steps_pct = [8, 4]", "step_type = \"log\"\nsteps_log10 = [0.1]"),
                           "a.toml");
  EXPECT_EQ(log.adaptive.staircase.step_type, StaircaseStepType::log);
  EXPECT_EQ(log.adaptive.staircase.steps, (std::vector<double>{0.1}));
  // Each step type has its steps in its own unit and key; K + N must fit in stop_reversals.
  EXPECT_EQ(error_of(replaced(kStaircase, "steps_pct = [8, 4]", "step_type = \"db\"\nsteps_pct = [8, 4]")),
            "bad.toml:9:13: staircase.steps_pct: step_type = \"db\" takes its steps as steps_db");
  EXPECT_EQ(error_of(replaced(kStaircase, "steps_pct = [8, 4]", "step_type = \"db\"")),
            "bad.toml:7:1: staircase.steps_db: step_type = \"db\" needs its steps as steps_db (e.g. steps_db = "
            "[4, 2, 1])");
  EXPECT_EQ(error_of(replaced(kStaircase, "steps_pct = [8, 4]", "step_type = \"log\"\nsteps_log10 = [0.1, 3]")),
            "bad.toml:9:15: staircase.steps_log10: each step must be > 0 and <= 2 (got 3)");
  EXPECT_EQ(error_of(replaced(kStaircase, "steps_pct = [8, 4]", "step_type = \"dB\"")),
            "bad.toml:8:13: staircase.step_type: expected \"linear\", \"db\" or \"log\", got \"dB\"");
  EXPECT_EQ(error_of(replaced(kStaircase, "steps_pct = [8, 4]", "discard_reversals = 5")),
            "bad.toml:8:21: staircase.discard_reversals: the first 5 reversals discarded and the last 8 averaged "
            "(threshold_reversals) need 13 reversals, and a track stops at 12 (stop_reversals): it would never have an "
            "estimate; lower one of them or raise stop_reversals");
  EXPECT_NO_THROW(test::parse_protocol(replaced(kStaircase, "steps_pct = [8, 4]", "discard_reversals = 4"), "a.toml"))
      << "4 discarded + 8 averaged = the 12 a track stops at";
}

const std::string kQuest =
    "name = \"q\"\ntask = \"2afc_harder\"\nprocedure = \"quest\"\nconditions = [\"both\"]\nseed = 1\n"
    "reference = \"wood\"\n[quest]\ntrials = 30\n[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n";

TEST(StudyProtocol, QuestsScaleAndPlacement) {
  const StudyProtocol log = test::parse_protocol(
      replaced(kQuest, "trials = 30",
               "trials = 30\nscale = \"log10\"\nprior_mean_log10 = 1.2\nprior_sd_log10 = 0.3\n"
               "placement = \"quantile\"\nquantile = 0.59"),
      "a.toml");
  EXPECT_EQ(log.adaptive.quest_model.scale, QuestScale::log10);
  EXPECT_EQ(log.adaptive.quest_prior.mean, 1.2);
  EXPECT_EQ(log.adaptive.quest_prior.sd, 0.3);
  EXPECT_EQ(log.adaptive.quest_model.placement, QuestPlacement::quantile);
  EXPECT_EQ(log.adaptive.quest_model.quantile, 0.59);
  const StudyProtocol log_defaults =
      test::parse_protocol(replaced(kQuest, "trials = 30", "scale = \"log10\""), "a.toml");
  EXPECT_NEAR(log_defaults.adaptive.quest_prior.mean, std::log10(20.0), 1e-12);
  EXPECT_EQ(log_defaults.adaptive.quest_prior.sd, 0.5);
  const StudyProtocol mode = test::parse_protocol(replaced(kQuest, "trials = 30", "placement = \"mode\""), "a.toml");
  EXPECT_EQ(mode.adaptive.quest_model.placement, QuestPlacement::mode);
  EXPECT_EQ(error_of(replaced(kQuest, "trials = 30", "scale = \"log10\"\nprior_mean_pct = 20")),
            "bad.toml:9:18: quest.prior_mean_pct: scale = \"log10\" takes its prior in log10 units of the difference: "
            "prior_mean_log10, prior_sd_log10");
  EXPECT_EQ(error_of(replaced(kQuest, "trials = 30", "prior_sd_log10 = 0.3")),
            "bad.toml:8:18: quest.prior_sd_log10: only scale = \"log10\" uses it (this prior is in %: prior_mean_pct, "
            "prior_sd_pct)");
  EXPECT_EQ(error_of(replaced(kQuest, "trials = 30", "quantile = 0.5")),
            "bad.toml:8:12: quest.quantile: only placement = \"quantile\" uses it");
  EXPECT_EQ(error_of(replaced(kQuest, "trials = 30", "placement = \"quantile\"\nquantile = 1")),
            "bad.toml:9:12: quest.quantile: must be in [0.01, 0.99], got 1");
  EXPECT_EQ(error_of(replaced(kQuest, "trials = 30", "scale = \"log\"")),
            "bad.toml:8:9: quest.scale: expected \"linear\" or \"log10\", got \"log\"");
  EXPECT_EQ(error_of(replaced(kQuest, "trials = 30", "scale = \"log10\"\nprior_mean_log10 = 2.5")),
            "bad.toml:9:20: quest.prior_mean_log10: must be in [-0.30103, 1.77815], got 2.5");
}

TEST(StudyProtocol, StrikeAnswersAreStatedInTheProtocol) {
  const StudyProtocol keys = load_shipped("example.toml");
  EXPECT_EQ(keys.response, StudyResponse::keys);
  const StudyProtocol s = load_shipped("strike.toml");
  EXPECT_EQ(s.response, StudyResponse::strike);
  EXPECT_EQ(s.answer_strike.voice, "click");
  EXPECT_FALSE(s.answer_strike.feel);  // no actuator signal, no bounce
  const std::string ok = replaced(test::kTwoAfcProtocol, "seed = 42", "seed = 42\nresponse = \"strike\"");
  const StudyProtocol defaults = test::parse_protocol(ok, "a.toml");
  EXPECT_EQ(defaults.response, StudyResponse::strike);
  EXPECT_EQ(defaults.answer_strike.voice, "click");
  EXPECT_FALSE(defaults.answer_strike.feel);
  const StudyProtocol felt =
      test::parse_protocol(ok + "[answer_strike]\nsound = \"none\"\nfeel = \"metal\"\n", "a.toml");
  EXPECT_EQ(felt.answer_strike.voice, "");
  ASSERT_TRUE(felt.answer_strike.feel);
  EXPECT_EQ(felt.answer_strike.feel->name, "metal");
  EXPECT_EQ(felt.answer_strike.feel->actuator.amplitude, test::percussion().materials[1].actuator.amplitude);
}

TEST(StudyProtocol, StrikeAnswerMistakesAreOneLineEach) {
  const std::string ok = test::kTwoAfcProtocol;
  EXPECT_EQ(error_of(replaced(ok, "seed = 42", "seed = 42\nresponse = \"voice\"")),
            "bad.toml:7:12: response: expected \"keys\" or \"strike\", got \"voice\"");
  const std::string strike = replaced(ok, "seed = 42", "seed = 42\nresponse = \"strike\"");
  EXPECT_EQ(error_of(strike + "[answer_strike]\nfeel = \"glass\"\n"),
            "bad.toml:25:8: answer_strike.feel: expected \"none\" or a material of the scene (wood, metal), got "
            "\"glass\"");
  EXPECT_EQ(error_of(ok + "[answer_strike]\nsound = \"click\"\n"),
            "bad.toml:23:1: answer_strike: only response = \"strike\" uses it");
}

TEST(StudyProtocol, ATextureProtocolAsksBumpOrHoleOrTheSteeper) {
  const StudyProtocol t = load_shipped("texture.toml");
  EXPECT_EQ(t.task, StudyTask::texture_slope);
  EXPECT_EQ(t.question, TextureQuestion::bump_or_hole);
  EXPECT_FALSE(t.paired());
  EXPECT_EQ(t.answer_choices(), (std::vector<std::string>{"bump", "hole"}));
  ASSERT_EQ(t.stimuli.size(), 4u);
  ASSERT_TRUE(t.stimuli[2].relief);
  EXPECT_EQ(t.stimuli[2].relief->shape, ReliefShape::hole);
  EXPECT_EQ(t.stimuli[2].relief->height_m, 0.004);
  EXPECT_EQ(t.items() * t.conditions.size() * static_cast<std::size_t>(t.repetitions), 32u);

  const std::string steeper =
      "name = \"s\"\ntask = \"texture_slope\"\nquestion = \"steeper\"\nconditions = [\"both\"]\n"
      "repetitions = 2\nseed = 1\n[[stimulus]]\nname = \"b4\"\nrelief = \"bump\"\nheight_m = 0.004\n"
      "[[stimulus]]\nname = \"b5\"\nrelief = \"bump\"\nheight_m = 0.005\n[[pair]]\na = \"b5\"\nb = \"b4\"\n";
  const StudyProtocol s = test::parse_protocol(steeper, "s.toml");
  EXPECT_TRUE(s.paired());
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_EQ(s.pairs[0].harder, s.pairs[0].a) << "the higher relief is the steeper";
  EXPECT_NEAR(s.pairs[0].difference_pct, 25.0, 1e-9);
  EXPECT_EQ(s.answer_choices(), (std::vector<std::string>{"1", "2"}));

  EXPECT_EQ(error_of(replaced(steeper, "height_m = 0.005", "height_m = 0.004")),
            "bad.toml:17:5: pair[0].b: \"steeper\" is the higher relief; these two are as high");
  EXPECT_EQ(error_of(replaced(steeper, "name = \"b5\"\nrelief = \"bump\"", "name = \"b5\"\nrelief = \"hole\"")),
            "bad.toml:17:5: pair[0].b: \"which was steeper\" compares two bumps or two holes");
  EXPECT_EQ(error_of(replaced(steeper, "question = \"steeper\"", "question = \"deeper\"")),
            "bad.toml:3:12: question: expected \"bump_or_hole\" or \"steeper\", got \"deeper\"");
  EXPECT_EQ(error_of(replaced(steeper, "seed = 1", "seed = 1\nresponse = \"strike\"")),
            "bad.toml:7:12: response: a texture_slope trial has no bars to strike: its answers are keys");
  EXPECT_EQ(error_of(replaced(steeper, "seed = 1", "seed = 1\nreference_bar = 0")),
            "bad.toml:7:17: reference_bar: a texture_slope trial strikes no bar; remove it");
  EXPECT_EQ(error_of(replaced(steeper, "relief = \"bump\"\nheight_m = 0.004", "relief = \"ridge\"\nheight_m = 0.004")),
            "bad.toml:9:10: stimulus[0].relief: expected \"bump\" or \"hole\", got \"ridge\"");
  const std::string bumps_only = replaced(replaced(steeper, "\"steeper\"", "\"bump_or_hole\""),
                                          "[[pair]]\na = \"b5\"\nb = \"b4\"\n", "");
  EXPECT_NE(error_of(bumps_only).find("stimulus: \"bump or hole\" needs at least one of each"), std::string::npos)
      << error_of(bumps_only);
}

TEST(StudyProtocol, AVisitorProtocolStatesItsOfferConsentTrialsAndTimeout) {
  const StudyProtocol v = load_shipped("visitor.toml");
  ASSERT_TRUE(v.visitor);
  EXPECT_EQ(v.response, StudyResponse::strike);
  EXPECT_EQ(v.visitor->offer, "Help science: 60 seconds, 6 taps");
  EXPECT_NE(v.visitor->consent.find("no time of day"), std::string::npos);
  EXPECT_EQ(v.visitor->trials, 6);
  EXPECT_EQ(v.visitor->answer_timeout, 20 * kNanosPerSecond);
  EXPECT_FALSE(load_shipped("strike.toml").visitor);
  const std::string keys = test::kTwoAfcProtocol;
  EXPECT_EQ(error_of(keys + "[visitor]\nconsent = \"ok\"\n"),
            "bad.toml:23:1: visitor: a visitor answers by striking: it needs response = \"strike\"");
  const std::string strike = replaced(keys, "seed = 42", "seed = 42\nresponse = \"strike\"");
  EXPECT_EQ(error_of(strike + "[visitor]\ntrials = 6\n"), "bad.toml:24:1: visitor.consent: missing (required)");
  EXPECT_EQ(error_of(strike + "[visitor]\nconsent = \"ok\"\ntrials = 0\n"),
            "bad.toml:26:10: visitor.trials: must be in [1, 50], got 0");
  const std::string one_material =
      "name = \"n\"\ntask = \"name_material\"\nconditions = [\"both\"]\nrepetitions = 1\nseed = 1\n"
      "response = \"strike\"\n[visitor]\nconsent = \"ok\"\n[[stimulus]]\nname = \"w\"\nmaterial = \"wood\"\n";
  EXPECT_NE(error_of(one_material).find("visitor: a visitor's consent is struck on the first two answer bars"),
            std::string::npos)
      << error_of(one_material);
}

TEST(StudyProtocol, AVisitorProtocolGivesItsWordsPerLanguageAndAnyOtherLanguageGetsItsOwnWhole) {
  // Issue 30: the shipped visitor study has words in every shipped language; a kiosk in a
  // language a protocol lacks shows it wholly in the protocol's own language.
  const StudyProtocol v = load_shipped("visitor.toml");
  ASSERT_TRUE(v.visitor);
  EXPECT_EQ(v.visitor->language, "en");
  for (const std::string& l : visitor_languages()) EXPECT_EQ(v.visitor->language_for(l), l);
  EXPECT_NE(v.visitor->text_in("de").consent.find("Schlag auf Ja"), std::string::npos);
  EXPECT_NE(v.visitor->text_in("fr").offer.find("Aide la science"), std::string::npos);
  EXPECT_NE(v.visitor->text_in("ar").consent.find("نعم"), std::string::npos);
  EXPECT_EQ(v.visitor->text_in("en").offer, v.visitor->offer);
  const std::string german_only =
      replaced(std::string(test::kTwoAfcProtocol), "seed = 42", "seed = 42\nresponse = \"strike\"") +
      "[visitor]\nconsent = \"ok\"\n[visitor.text.de]\noffer = \"Hilf\"\nconsent = \"gut\"\n";
  const StudyProtocol g = test::parse_protocol(german_only, "german.toml");
  EXPECT_EQ(g.visitor->language_for("de"), "de");
  EXPECT_EQ(g.visitor->language_for("ja"), "en");
  EXPECT_EQ(g.visitor->text_in("ja").consent, "ok");
  // Each language's words are checked as the protocol's own; an unknown language, or the
  // protocol's own given twice, is refused at its line.
  const std::string strike =
      replaced(std::string(test::kTwoAfcProtocol), "seed = 42", "seed = 42\nresponse = \"strike\"") +
      "[visitor]\nconsent = \"ok\"\n";
  EXPECT_EQ(error_of(strike + "[visitor.text.de]\noffer = \"Hilf\"\n"),
            "bad.toml:26:1: visitor.text.de.consent: missing (required)");
  EXPECT_EQ(error_of(strike + "[visitor.text.xx]\noffer = \"a\"\nconsent = \"b\"\n"),
            "bad.toml:26:1: visitor.text.xx: \"xx\": not a language the kiosk has (" + visitor_languages_text() + ")");
  EXPECT_EQ(error_of(strike + "[visitor.text.en]\noffer = \"a\"\nconsent = \"b\"\n"),
            "bad.toml:26:1: visitor.text.en: is the protocol's own language ([visitor] language): its words are "
            "[visitor]'s");
  EXPECT_EQ(error_of(replaced(strike, "consent = \"ok\"", "consent = \"ok\"\nlanguage = \"xx\"")),
            "bad.toml:26:12: visitor.language: \"xx\": not a language the kiosk has (" + visitor_languages_text() + ")");
}

}  // namespace
}  // namespace mallet::study
