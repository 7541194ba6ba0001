// `mallet doctor`'s language check (issue 30): a shipped language shown is whole; a language an
// operator dropped in is counted against the template, its untranslated texts and the letters
// no font has named, with the file to fix.
#include <cstdlib>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "app/kiosk/doctor.hpp"
#include "app/kiosk/language_check.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

// How many texts the code marks today: po/mallet.pot's msgids (po.pot_current holds it current).
int template_texts() {
  std::ifstream pot(std::string(MALLET_TEST_SOURCE_DIR) + "/po/mallet.pot");
  std::string line;
  int n = 0;
  while (std::getline(pot, line)) n += line.rfind("msgid \"", 0) == 0 && line != "msgid \"\"";
  return n;
}

class LanguageCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir();
    setenv("MALLET_LOCALE_DROPIN", dir_.c_str(), 1);
    std::vector<std::string> problems;
    start_visitor_language("en", problems);
  }
  void TearDown() override {
    unsetenv("MALLET_LOCALE_DROPIN");
    load_dropin_catalogues();
    use_visitor_language("en");
  }
  std::filesystem::path dir_;
};

TEST_F(LanguageCheck, ShippedLanguagesShownAreWholeAndInTheirFonts) {
  AppConfig c;
  c.language = "ar";
  c.attract.languages = {"ar", "hi", "en"};
  const DoctorCheck check = check_language(c);
  EXPECT_EQ(check.name, "language");
  EXPECT_EQ(check.level, CheckLevel::ok) << check.found;
  const std::string all = std::to_string(template_texts()) + " of " + std::to_string(template_texts());
  ASSERT_GT(template_texts(), 50);
  EXPECT_EQ(check.found, "ar: " + all + " texts in Noto Sans Arabic; hi: " + all + " texts in Noto Sans Devanagari; " +
                             "en: the texts as written");
}

TEST_F(LanguageCheck, ADroppedInLanguageNamesItsGapsAndTheFileToFix) {
  // Two texts, one with a letter no font has (U+E000, private use).
  std::ofstream(dir_ / "eo.po") << "msgid \"\"\nmsgstr \"\"\n\"Content-Type: text/plain; charset=UTF-8\\n\"\n\n"
                                   "msgid \"Yes\"\nmsgstr \"Jes\"\n\nmsgid \"No\"\nmsgstr \"Ne \xEE\x80\x80\"\n";
  load_dropin_catalogues();
  AppConfig c;
  c.language = "eo";
  const DoctorCheck check = check_language(c);
  EXPECT_EQ(check.level, CheckLevel::warn);
  EXPECT_EQ(check.found.rfind("eo: 2 of " + std::to_string(template_texts()) + " texts in ", 0), 0u) << check.found;
  EXPECT_NE(check.found.find(", untranslated: \""), std::string::npos) << check.found;
  // Three untranslated texts named, the rest counted.
  EXPECT_NE(check.found.find("and " + std::to_string(template_texts() - 5) + " more (shown in English)"),
            std::string::npos)
      << check.found;
  EXPECT_NE(check.found.find("no font has: \xEE\x80\x80 (U+E000)"), std::string::npos) << check.found;
  EXPECT_NE(check.fix.find("translate them in " + (dir_ / "eo.po").string()), std::string::npos) << check.fix;
  EXPECT_NE(check.fix.find("[fonts] eo = "), std::string::npos) << check.fix;
}

TEST_F(LanguageCheck, ThePagesDoctorSaysTheLanguageOnTheScreenAfterTheOperatorsL) {
  // The page's D said "shown: ar" after L had switched the kiosk to English (issue 48, item
  // 13): the settings' language and the one on the screen, each named.
  std::ofstream(dir_ / "mallet.toml") << "[kiosk]\nlanguage = \"ar\"\n";
  setenv("MALLET_STATE_DIR", (dir_ / "state").c_str(), 1);
  DoctorOptions o;
  o.config = dir_ / "mallet.toml";
  o.config_dir = dir_ / "mallet.d";
  KioskDeviceFacts facts;
  auto languages = [&] {
    for (const DoctorCheck& c : run_doctor_with(o, facts))
      if (c.name == "languages") return c.found;
    return std::string("no languages check");
  };
  EXPECT_NE(languages().find("; shown: ar"), std::string::npos) << languages();
  facts.shown_language = "en";
  EXPECT_NE(languages().find("; shown: en (the page's L; the settings: ar)"), std::string::npos) << languages();
  facts.shown_language = "ar";
  EXPECT_EQ(languages().find("the page's L"), std::string::npos) << languages();
  unsetenv("MALLET_STATE_DIR");
}

}  // namespace
}  // namespace mallet::app
