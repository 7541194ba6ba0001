// Which language the kiosk shows: [attract] languages in turn from the moment Attract
// began, the one on the screen kept by a visitor who starts playing, the operator's L.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/language_choice.hpp"
#include "core/visitor_language.hpp"

namespace mallet {
namespace {

constexpr Nanos kSecond = 1'000'000'000;

TEST(LanguageChoice, WithoutAttractLanguagesIsTheKiosksLanguageThroughout) {
  LanguageChoice c("fr", {}, 15 * kSecond);
  EXPECT_EQ(c.at(KioskState::attract, 0, 0), "fr");
  EXPECT_EQ(c.at(KioskState::attract, 0, 1000 * kSecond), "fr");
  EXPECT_EQ(c.at(KioskState::play, 1000 * kSecond, 1001 * kSecond), "fr");
}

TEST(LanguageChoice, AttractShowsEachLanguageInTurnForItsSpan) {
  LanguageChoice c("en", {"en", "de", "ja"}, 15 * kSecond);
  const Nanos since = 100 * kSecond;
  EXPECT_EQ(c.at(KioskState::attract, since, since), "en");
  EXPECT_EQ(c.at(KioskState::attract, since, since + 15 * kSecond - 1), "en");  // to the nanosecond
  EXPECT_EQ(c.at(KioskState::attract, since, since + 15 * kSecond), "de");
  EXPECT_EQ(c.at(KioskState::attract, since, since + 44 * kSecond), "ja");
  EXPECT_EQ(c.at(KioskState::attract, since, since + 45 * kSecond), "en");  // and round again
}

TEST(LanguageChoice, AVisitorWhoStartsPlayingKeepsTheLanguageOnTheScreen) {
  LanguageChoice c("en", {"en", "de"}, 10 * kSecond);
  EXPECT_EQ(c.at(KioskState::attract, 0, 12 * kSecond), "de");
  EXPECT_EQ(c.at(KioskState::play, 12 * kSecond, 13 * kSecond), "de");
  EXPECT_EQ(c.at(KioskState::play, 12 * kSecond, 500 * kSecond), "de");
  // Back in Attract, the turn starts again with the first.
  EXPECT_EQ(c.at(KioskState::attract, 600 * kSecond, 600 * kSecond), "en");
}

TEST(LanguageChoice, TheOperatorsLCyclesEveryShippedLanguageAndTheChoiceStays) {
  LanguageChoice c("en", {}, 10 * kSecond);
  std::vector<std::string> seen;
  const std::vector<std::string> all = visitor_languages();  // en first
  for (std::size_t i = 0; i < all.size() + 1; ++i) seen.push_back(c.next());
  std::vector<std::string> want(all.begin() + 1, all.end());
  want.insert(want.end(), {"en", "de"});
  EXPECT_EQ(seen, want);
  EXPECT_EQ(c.at(KioskState::operator_page, 0, kSecond), "de");
  EXPECT_EQ(c.at(KioskState::attract, 2 * kSecond, 3 * kSecond), "de");  // the kiosk's language now
}

}  // namespace
}  // namespace mallet
