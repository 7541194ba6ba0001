// An enum's names written once (core/enum_names.hpp): every table the settings, the CSVs
// and the journal read names each value once, with a word of its own, both ways round.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "core/app_config.hpp"
#include "core/calibration_session.hpp"
#include "core/contact_predictor.hpp"
#include "core/doctor_check.hpp"
#include "core/enum_names.hpp"
#include "core/ir_tracker.hpp"
#include "core/kiosk_states.hpp"
#include "core/present_clock.hpp"
#include "core/scene.hpp"
#include "core/stroke_corpus.hpp"
#include "core/study/study_protocol.hpp"
#include "core/texture_relief.hpp"

namespace mallet {
namespace {

//! No two entries share a value or a word, and each word reads back as its own value.
template <typename E, std::size_t N>
void expect_one_word_per_value(const EnumNames<E, N>& names) {
  std::set<E> values;
  std::set<std::string> words;
  for (const auto& [value, name] : names) {
    EXPECT_TRUE(values.insert(value).second) << name << " names a value twice";
    EXPECT_TRUE(words.insert(name).second) << name << " is used twice";
    EXPECT_EQ(value_named(names, name), value) << name;
    EXPECT_STREQ(name_in(names, value), name);
  }
}

TEST(EnumNames, EveryTableNamesEachValueOnceBothWaysRound) {
  expect_one_word_per_value(kQualityNames);
  expect_one_word_per_value(kCueAlignNames);
  expect_one_word_per_value(kPresentPacingNames);
  expect_one_word_per_value(kCheckLevelNames);
  expect_one_word_per_value(kIrTrackerEventNames);
  expect_one_word_per_value(kKioskStateNames);
  expect_one_word_per_value(kCalibrationStepNames);
  expect_one_word_per_value(kStrokeKindNames);
  expect_one_word_per_value(kPredictionVerdictNames);
  expect_one_word_per_value(kReliefShapeNames);
  expect_one_word_per_value(kReliefProfileNames);
  expect_one_word_per_value(kSceneKindNames);
  expect_one_word_per_value(study::kStudyTaskNames);
  expect_one_word_per_value(study::kTextureQuestionNames);
  expect_one_word_per_value(study::kStudyConditionNames);
  expect_one_word_per_value(study::kStudyProcedureNames);
  expect_one_word_per_value(study::kStudyResponseNames);
}

TEST(EnumNames, AWordNotInTheTableNamesNothingAndAValueNotInItGetsTheFallback) {
  EXPECT_EQ(value_named(kQualityNames, "Fast"), std::nullopt);
  EXPECT_EQ(value_named(kQualityNames, ""), std::nullopt);
  EXPECT_STREQ(name_in(kQualityNames, static_cast<Quality>(9)), "?");
  EXPECT_STREQ(name_in(kPresentPacingNames, static_cast<PresentPacing>(9), "fifo"), "fifo");
  EXPECT_EQ(name_in(kPresentPacingNames, static_cast<PresentPacing>(9), nullptr), nullptr);
}

TEST(EnumNames, TheWordsAreQuotedForAMessageAsAList) {
  EXPECT_EQ(quoted_names(kQualityNames), "\"fast\", \"balanced\" or \"exact\"");
  EXPECT_EQ(quoted_names(kCueAlignNames), "\"asap\" or \"picture\"");
  constexpr EnumNames<int, 1> one{{{7, "seven"}}};
  EXPECT_EQ(quoted_names(one), "\"seven\"");
}

TEST(EnumNames, TheKiosksNamesAreTheOnesItsJournalAndMetricsAlwaysUsed) {
  EXPECT_STREQ(to_string(KioskState::operator_page), "operator");
  EXPECT_STREQ(to_string(CueAlign::picture), "picture");
  EXPECT_STREQ(to_string(SceneKind::wall), "wall");
  EXPECT_EQ(study::task_name(study::StudyTask::two_afc_harder), "2afc_harder");
}

}  // namespace
}  // namespace mallet
