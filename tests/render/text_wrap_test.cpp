// Lines that fit a width: broken at spaces, or between Japanese characters but never before
// closing or after opening punctuation; each line as the font measures it, nothing lost.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/font_atlas.hpp"
#include "render/text_wrap.hpp"

namespace mallet::render {
namespace {

const FontAtlas& font() {
  static const FontAtlas baked(FontAtlas::default_font(), 20.0f,
                               "マレットを持って、鍵盤をたたいてみよう（保存しません）", FontAtlas::default_cjk_font());
  return baked;
}

std::string joined(const std::vector<std::string>& lines, const char* between) {
  std::string all;
  for (std::size_t i = 0; i < lines.size(); ++i) all += (i ? between : "") + lines[i];
  return all;
}

TEST(TextWrap, TextThatFitsIsOneLine) {
  const std::string text = "Pick up the mallet and strike a bar";
  EXPECT_EQ(wrap_text(font(), text, font().measure(text)), std::vector<std::string>{text});
  EXPECT_TRUE(wrap_text(font(), "", 100).empty());
  EXPECT_TRUE(wrap_text(font(), "   ", 100).empty());
}

TEST(TextWrap, BreaksAtSpacesAndEachLineFits) {
  const std::string text = "Nimm den Schlägel und schlag auf einen Klangstab";
  const float width = font().measure(text) * 0.55f;
  const std::vector<std::string> lines = wrap_text(font(), text, width);
  ASSERT_EQ(lines.size(), 2u);
  for (const std::string& l : lines) {
    EXPECT_LE(font().measure(l), width) << l;
    EXPECT_NE(l.front(), ' ');
    EXPECT_NE(l.back(), ' ');
  }
  EXPECT_EQ(joined(lines, " "), text);  // only the spaces at the breaks are gone
  // Greedy: the first line could not have taken the second's first word.
  const std::string longer = lines[0] + " " + lines[1].substr(0, lines[1].find(' '));
  EXPECT_GT(font().measure(longer), width);
}

TEST(TextWrap, JapaneseBreaksBetweenCharactersButNotBeforeClosingPunctuation) {
  const std::string text = "マレットを持って、鍵盤をたたいてみよう";
  // Narrow enough that a greedy break would otherwise fall right before "、".
  const std::string head = "マレットを持って";
  const float width = font().measure(head) + font().glyph(U'、').advance * 0.5f;
  const std::vector<std::string> lines = wrap_text(font(), text, width);
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(joined(lines, ""), text);  // no spaces to drop: every character kept
  for (const std::string& l : lines) {
    EXPECT_LE(font().measure(l), width) << l;
    EXPECT_NE(l.rfind("、", 0), 0u) << "a line begins with a closing comma: " << l;
  }
}

TEST(TextWrap, OpeningPunctuationStaysWithWhatItOpens) {
  const std::vector<std::string> lines =
      wrap_text(font(), "鍵盤（保存しません）", font().measure("鍵盤（") + 1.0f);
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines[0], "鍵盤");  // not "鍵盤（"
  EXPECT_EQ(joined(lines, ""), "鍵盤（保存しません）");
}

TEST(TextWrap, AWordWiderThanTheLineIsCutBetweenCharacters) {
  const std::string word = "Rückprojektionsfehler";
  const float width = font().measure(word) / 3;
  const std::vector<std::string> lines = wrap_text(font(), word, width);
  EXPECT_GE(lines.size(), 3u);
  EXPECT_EQ(joined(lines, ""), word);  // ü kept whole: cuts fall between characters
  for (const std::string& l : lines) EXPECT_LE(font().measure(l), width) << l;
}

}  // namespace
}  // namespace mallet::render
