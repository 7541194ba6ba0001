// The second paper's texture study (task = "texture_slope") headless: each trial crosses the
// disc through the texture scene's own route and engine; what a condition presented is
// measured on that output (the Speed technique's cursor offset, the stripes on the actuator).
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "app/study/study_session.hpp"
#include "app/study/study_stimuli.hpp"
#include "core/study/results_csv.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

StudyOptions texture_options(const fs::path& dir, const fs::path& protocol) {
  StudyOptions o;
  o.protocol = protocol;
  o.participant = "T1";
  o.out = dir / "t.csv";  // no --scene: the shipped texture scene, for a texture protocol
  return o;
}

TEST(StudyTexture, EachConditionPresentsItsCuesAndTheAnswersAreBumpOrHole) {
  const fs::path dir = test::scratch_dir();
  const StudyRunResult r = run_study(texture_options(dir, test::config_dir() / "study" / "texture.toml"));
  EXPECT_EQ(r.answered, 32);
  const std::vector<study::ResultRow> rows = study::read_results(dir / "t.csv").rows;
  ASSERT_EQ(rows.size(), 32u);
  for (const study::ResultRow& row : rows) {
    EXPECT_EQ(row.task, "texture_slope");
    EXPECT_TRUE(row.answer == "bump" || row.answer == "hole") << row.answer;
    EXPECT_EQ(row.correct, row.answer == row.stimuli.substr(0, 4)) << row.stimuli;
    const bool visual = row.condition == "visual_only" || row.condition == "both";
    const bool tactile = row.condition == "tactile_only" || row.condition == "both";
    // The Speed technique moves the cursor off the hand by millimetres on a 4-8 mm relief;
    // without it the cursor is the hand.
    EXPECT_EQ(row.visual_peak_m > 1e-3, visual) << row.trial << " " << row.condition << " " << row.visual_peak_m;
    EXPECT_EQ(row.visual_peak_m < 1e-9, !visual) << row.trial;
    EXPECT_EQ(row.actuator_peak > 0.01, tactile) << row.trial << " " << row.condition << " " << row.actuator_peak;
    EXPECT_EQ(row.actuator_peak == 0.0, !tactile) << row.trial;
    EXPECT_TRUE(std::isnan(row.actuator_onset_ms)) << "a crossing is not a strike";
    EXPECT_TRUE(std::isnan(row.difference_pct));
  }
  // A higher relief moves the cursor further off the hand.
  double small = 0, large = 0;
  for (const study::ResultRow& row : rows)
    if (row.condition == "both") (row.stimuli.ends_with("4mm") ? small : large) = row.visual_peak_m;
  EXPECT_GT(large, 1.5 * small);
}

TEST(StudyTexture, WhichWasSteeperCrossesTwiceAndIsFitLikeA2afc) {
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "s.toml")
      << "name = \"s\"\ntask = \"texture_slope\"\nquestion = \"steeper\"\nconditions = [\"visual_only\", \"none\"]\n"
         "repetitions = 2\nseed = 5\n[timing]\nlead_s = 0.1\nstimulus_s = 1.0\nstimulus_interval_s = 1.2\n"
         "inter_trial_s = 0.1\n"
         "[[stimulus]]\nname = \"b4\"\nrelief = \"bump\"\nheight_m = 0.004\n"
         "[[stimulus]]\nname = \"b6\"\nrelief = \"bump\"\nheight_m = 0.006\n"
         "[[pair]]\na = \"b4\"\nb = \"b6\"\n";
  const StudyRunResult r = run_study(texture_options(dir, dir / "s.toml"));
  EXPECT_EQ(r.answered, 4);
  const std::vector<study::ResultRow> rows = study::read_results(dir / "t.csv").rows;
  ASSERT_EQ(rows.size(), 4u);
  for (const study::ResultRow& row : rows) {
    EXPECT_TRUE(row.answer == "1" || row.answer == "2");
    EXPECT_NEAR(row.difference_pct, 50.0, 1e-9);
    EXPECT_TRUE(row.stimuli == "b4|b6" || row.stimuli == "b6|b4") << row.stimuli;
    EXPECT_EQ(row.correct, row.answer == (row.stimuli == "b6|b4" ? "1" : "2"));
  }
}

TEST(StudyTexture, APercussionProtocolOnATextureSceneAndTheOtherWayRoundAreRefused) {
  const fs::path dir = test::scratch_dir();
  StudyOptions o = texture_options(dir, test::config_dir() / "study" / "example.toml");
  o.scene = test::texture_scene();
  EXPECT_THROW(
      {
        try {
          plan_study(o);
        } catch (const FileError& e) {
          EXPECT_NE(std::string(e.what()).find("task: \"2afc_harder\" strikes bars, and the scene has none"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      FileError);
  o = texture_options(dir, test::config_dir() / "study" / "texture.toml");
  o.scene = test::percussion_scene();
  try {
    plan_study(o);
    ADD_FAILURE() << "no error";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("task texture_slope needs a texture scene"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mallet::app
