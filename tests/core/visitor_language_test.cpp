// The visitor's language: the texts come from the catalogues msgfmt built from po/*.po
// (MALLET_LOCALE_DIR, set by the test runner), English is the code's own text, a language
// switches live, and a catalogue that is missing or malformed is a one-line problem.
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/catalogue_file.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/file_error.hpp"
#include "core/kiosk_states.hpp"
#include "core/visitor_language.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

std::filesystem::path built_catalogues() {
  const char* dir = std::getenv("MALLET_LOCALE_DIR");
  return dir ? dir : "";
}

class VisitorLanguage : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(built_catalogues().empty()) << "run through ctest: it sets MALLET_LOCALE_DIR";
    bind_visitor_catalogues(built_catalogues());
  }
  void TearDown() override { use_visitor_language("en"); }
};

TEST(VisitorLanguages, AreEnglishAndEachCatalogueInPoLinguas) {
  std::ifstream in(test::source_dir() / "po" / "LINGUAS");
  std::vector<std::string> expected{"en"};
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') expected.push_back(line);
  EXPECT_EQ(visitor_languages(), expected);
  EXPECT_EQ(visitor_languages_text(), "en, de, fr, ja, zh, ko, ar, he, hi");
  EXPECT_TRUE(is_visitor_language("ja"));
  EXPECT_FALSE(is_visitor_language("JA"));
  EXPECT_FALSE(is_visitor_language(""));
}

TEST_F(VisitorLanguage, EveryShippedLanguageInvitesInItsOwnWords) {
  EXPECT_STREQ(hint_text(KioskHint::invitation).data(), "Pick up the mallet and strike a bar");
  use_visitor_language("de");
  EXPECT_EQ(visitor_language(), "de");
  EXPECT_EQ(hint_text(KioskHint::invitation), "Nimm den Schlägel und schlag auf einen Klangstab");
  EXPECT_EQ(hint_text(KioskHint::invitation, SceneKind::wall), "Nimm den Schlägel und klopfe an die Wand");
  use_visitor_language("fr");  // switched live: the next lookup answers in the new language
  EXPECT_EQ(hint_text(KioskHint::invitation), "Prends la mailloche et frappe une lame");
  use_visitor_language("ja");
  EXPECT_EQ(hint_text(KioskHint::invitation), "マレットを持って、鍵盤をたたいてみよう");
  EXPECT_STREQ(tr("Thank you"), "ありがとうございました");
  use_visitor_language("en");
  EXPECT_EQ(hint_text(KioskHint::invitation), "Pick up the mallet and strike a bar");
}

TEST_F(VisitorLanguage, EveryVisitorLineIsShortEnoughToReadAtAGlance) {
  // The Smithsonian Guidelines for Accessible Exhibition Design (section B, label text): at
  // most 55 characters a line on average, and no sentence over 25 words. Each hint is one
  // line; counted in characters (code points), not bytes.
  for (const std::string& language : visitor_languages()) {
    use_visitor_language(language);
    for (const KioskHint hint : {KioskHint::invitation, KioskHint::point_at_screen, KioskHint::close_needs_chord,
                                 KioskHint::remote_missing})
      for (const SceneKind scene : {SceneKind::percussion, SceneKind::texture, SceneKind::wall})
        for (const bool mouse : {false, true}) {
          const std::string_view text = hint_text(hint, scene, mouse);
          std::size_t characters = 0, words = 1;
          for (const char c : text) {
            characters += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
            words += c == ' ';
          }
          EXPECT_GT(characters, 0u);
          EXPECT_LE(characters, 55u) << language << ": " << text;
          EXPECT_LE(words, 25u) << language << ": " << text;
        }
  }
}

TEST_F(VisitorLanguage, AnUnknownLanguageOrTextShowsTheEnglish) {
  use_visitor_language("xx");
  EXPECT_EQ(visitor_language(), "en");
  use_visitor_language("de");
  EXPECT_STREQ(tr("a text no catalogue has"), "a text no catalogue has");
}

TEST_F(VisitorLanguage, NumbersStillReadWithAPointWhateverTheLanguage) {
  use_visitor_language("de");  // only LC_MESSAGES changed: the settings' 0.5 is not "0,5"
  const AppConfig c = config::parse_app_config("[attract]\nvolume = 0.5\n", "c.toml");
  EXPECT_EQ(c.attract.volume, 0.5);
  std::ostringstream out;
  out << 0.25;
  EXPECT_EQ(out.str(), "0.25");
}

TEST(CatalogueTexts, HoldEveryTranslationForTheFont) {
  std::vector<std::string> problems;
  const std::string texts = catalogue_texts(built_catalogues(), problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  EXPECT_NE(texts.find("Schlägel"), std::string::npos);
  EXPECT_NE(texts.find("Étalonnage"), std::string::npos);
  EXPECT_NE(texts.find("鍵盤"), std::string::npos);
  EXPECT_NE(texts.find("نعم"), std::string::npos);  // Arabic's Yes
  EXPECT_EQ(texts.find("Project-Id-Version"), std::string::npos);  // not the catalogues' headers
}

TEST(CatalogueTexts, AMissingOrMalformedCatalogueIsOneLineNamingItsFileAndByte) {
  const std::filesystem::path dir = test::scratch_dir();
  for (const char* l : {"de", "fr", "ja"}) std::filesystem::create_directories(dir / l / "LC_MESSAGES");
  std::ofstream(dir / "de" / "LC_MESSAGES" / "mallet.mo") << "not a catalogue at all, but long enough";
  // A real header whose translation table lies far past the end of the file.
  std::string cut(28, '\0');
  const unsigned char header[] = {0xde, 0x12, 0x04, 0x95, 0, 0, 0, 0, 5, 0, 0, 0, 28, 0, 0, 0, 0xff, 0xff, 0, 0};
  for (std::size_t i = 0; i < sizeof header; ++i) cut[i] = static_cast<char>(header[i]);
  std::ofstream(dir / "fr" / "LC_MESSAGES" / "mallet.mo", std::ios::binary) << cut;
  std::vector<std::string> problems;
  EXPECT_EQ(catalogue_texts(dir, problems), "");
  ASSERT_EQ(problems.size(), visitor_languages().size() - 1);  // the others: no file at all
  EXPECT_EQ(problems[0], (dir / "de" / "LC_MESSAGES" / "mallet.mo").string() +
                             ": byte 0: not a gettext catalogue (.mo): wrong magic number");
  EXPECT_NE(problems[1].find("fr/LC_MESSAGES/mallet.mo: byte 12: its table of texts runs past the end"),
            std::string::npos)
      << problems[1];
  EXPECT_NE(problems[2].find("ja/LC_MESSAGES/mallet.mo: cannot open the catalogue"), std::string::npos)
      << problems[2];
}

// A msgid holding a newline whose translation has another directive: the problem quotes the
// text with its newline escaped, so it stays one line (found by fuzz_catalogue).
TEST(CatalogueTexts, AProblemQuotingATextWithANewlineIsStillOneLine) {
  const std::string id = "two\nlines %d", text = "zwei\nZeilen %s";
  // A .mo file of one entry: the header (7 words), the tables (one pair each), the strings.
  std::string mo;
  const auto put = [&](std::uint32_t w) {
    for (int i = 0; i < 4; ++i) mo += static_cast<char>((w >> (8 * i)) & 0xff);
  };
  const std::uint32_t strings = 28 + 16;
  for (const std::uint32_t w : {0x950412deu, 0u, 1u, 28u, 36u, 0u, 0u}) put(w);
  put(static_cast<std::uint32_t>(id.size()));
  put(strings);
  put(static_cast<std::uint32_t>(text.size()));
  put(strings + static_cast<std::uint32_t>(id.size()) + 1);
  mo += id + '\0' + text + '\0';
  const std::filesystem::path file = test::scratch_dir() / "nl.mo";
  std::ofstream(file, std::ios::binary) << mo;
  std::vector<std::string> problems;
  const Catalogue c = read_catalogue(file, problems);
  EXPECT_TRUE(c.read);
  EXPECT_TRUE(c.texts.empty());  // shown in English
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0], file.string() + ": the translation of \"two\\nlines %d\" has other printf directives "
                                         "than the text (\"s\" instead of \"d\"): shown in English");
}

// A language added without rebuilding: an operator drops eo.po into the drop-in folder,
// and the settings take [kiosk] language = "eo"; tr() answers from it, a text it lacks in
// English; a broken file is one line naming its place and the language is not offered.
class DroppedInLanguage : public VisitorLanguage {
 protected:
  void SetUp() override {
    VisitorLanguage::SetUp();
    dir_ = test::scratch_dir();
    setenv("MALLET_LOCALE_DROPIN", dir_.c_str(), 1);
  }
  void TearDown() override {
    unsetenv("MALLET_LOCALE_DROPIN");
    load_dropin_catalogues();
    VisitorLanguage::TearDown();
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  static std::string po(const std::string& entries) {
    return "msgid \"\"\nmsgstr \"\"\n\"Content-Type: text/plain; charset=UTF-8\\n\"\n\n" + entries;
  }
  std::filesystem::path dir_;
};

TEST_F(DroppedInLanguage, APoFileDroppedInIsALanguageTheSettingsTake) {
  write("eo.po", po("msgid \"Yes\"\nmsgstr \"Jes\"\n\n#, c-format\nmsgid \"Tap %d\"\nmsgstr \"Frapeto %d\"\n"));
  EXPECT_THROW(config::parse_app_config("[kiosk]\nlanguage = \"xx\"\n", "c.toml"), FileError);
  const AppConfig c = config::parse_app_config("[kiosk]\nlanguage = \"eo\"\n", "c.toml");  // read on demand
  EXPECT_EQ(c.language, "eo");
  EXPECT_TRUE(is_visitor_language("eo"));
  EXPECT_EQ(visitor_languages().back(), "eo");
  EXPECT_EQ(dropin_catalogue("eo"), dir_ / "eo.po");
  use_visitor_language("eo");
  EXPECT_STREQ(tr("Yes"), "Jes");
  EXPECT_STREQ(tr("Tap %d"), "Frapeto %d");
  EXPECT_STREQ(tr("No"), "No");  // not translated: English
  // Read again unchanged (a reload), the same catalogue goes on: the same text, at the same place.
  const char* yes = tr("Yes");
  EXPECT_TRUE(load_dropin_catalogues().empty());
  EXPECT_EQ(tr("Yes"), yes);
}

TEST_F(DroppedInLanguage, ACompiledCatalogueAndAShippedLanguagesReplacementWork) {
  // de.mo compiled from a .po: it replaces the shipped German where it has a text.
  write("de-src.po", po("msgid \"Yes\"\nmsgstr \"Jawohl\"\n"));
  const std::string msgfmt = "msgfmt -o '" + (dir_ / "de.mo").string() + "' '" + (dir_ / "de-src.po").string() + "'";
  ASSERT_EQ(std::system(msgfmt.c_str()), 0);
  std::filesystem::remove(dir_ / "de-src.po");
  EXPECT_TRUE(load_dropin_catalogues().empty());
  use_visitor_language("de");
  EXPECT_STREQ(tr("Yes"), "Jawohl");
  EXPECT_STREQ(tr("No"), "Nein");  // the shipped catalogue's
  EXPECT_EQ(visitor_languages().size(), 9u);  // no new language: de was shipped
}

TEST_F(DroppedInLanguage, ABrokenFileIsOneLineNamingItsPlaceAndIsNotOffered) {
  write("eo.po", po("msgid \"Yes\"\nmsgstr \"Jes\n"));  // an unterminated string
  write("xh.mo", "not a catalogue at all, but long enough");
  const std::vector<std::string> problems = load_dropin_catalogues();
  ASSERT_EQ(problems.size(), 2u) << problems.front();
  EXPECT_EQ(problems[0], (dir_ / "eo.po").string() + ":7: end-of-line within string") << problems[0];
  EXPECT_EQ(problems[1], (dir_ / "xh.mo").string() + ": byte 0: not a gettext catalogue (.mo): wrong magic number");
  EXPECT_FALSE(is_visitor_language("eo"));
  EXPECT_FALSE(is_visitor_language("xh"));
  for (const std::string& p : problems) EXPECT_EQ(p.find('\n'), std::string::npos) << p;
}

TEST_F(DroppedInLanguage, ATranslationWithOtherPrintfDirectivesIsShownInEnglish) {
  // "%s" where the text prints a number would print garbage or crash: that entry is left out.
  write("eo.po", po("msgid \"Yes\"\nmsgstr \"Jes\"\n\nmsgid \"Tap %d\"\nmsgstr \"Frapeto %s\"\n"));
  const std::vector<std::string> problems = load_dropin_catalogues();
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("\"Tap %d\" has other printf directives"), std::string::npos) << problems[0];
  use_visitor_language("eo");
  EXPECT_STREQ(tr("Tap %d"), "Tap %d");
  EXPECT_STREQ(tr("Yes"), "Jes");
}

}  // namespace
}  // namespace mallet
