// Text set as the desktop sets it: an Arabic and a Devanagari line give the same glyphs, in
// the same order, as HarfBuzz's own tool (hb-shape) gives for the same font, so letters join
// and conjuncts form; a right-to-left line runs right to left, with a left-to-right run
// inside it kept in its own order.
#include <array>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/font_atlas.hpp"
#include "render/text_shaping.hpp"

namespace mallet::render {
namespace {

const FontAtlas& shaping_font() {
  static const FontAtlas made(24.0f);
  return made;
}

//! hb-shape's glyph ids for `text` in `face`, in its output's (visual) order.
std::vector<std::uint32_t> hb_shape(const Face& face, const std::string& language, const std::string& text) {
  const std::string command = std::string(MALLET_HB_SHAPE) + " --no-glyph-names --no-positions --no-clusters" +
                              " --face-index=" + std::to_string(face.index()) + " --language=" + language + " '" +
                              face.file().string() + "' '" + text + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  EXPECT_TRUE(pipe) << command;
  std::string out;
  std::array<char, 512> buffer{};
  while (pipe && std::fgets(buffer.data(), buffer.size(), pipe.get())) out += buffer.data();
  // "[123|45|6]"
  std::vector<std::uint32_t> ids;
  std::string inner = out.substr(out.find('[') + 1, out.rfind(']') - out.find('[') - 1);
  std::istringstream in(inner);
  for (std::string id; std::getline(in, id, '|');) ids.push_back(static_cast<std::uint32_t>(std::stoul(id)));
  return ids;
}

std::vector<std::uint32_t> ids_of(const ShapedText& s) {
  std::vector<std::uint32_t> ids;
  for (const PlacedGlyph& g : s.glyphs) ids.push_back(g.glyph);
  return ids;
}

TEST(TextShaping, ArabicJoinsAsHarfBuzzsOwnToolJoinsIt) {
  const std::string text = "ارفع المطرقة واضرب أحد القضبان";
  const ShapedText shaped = shaping_font().shape_in("ar", text);
  ASSERT_FALSE(shaped.glyphs.empty());
  const Face& face = *shaped.glyphs.front().face;
  EXPECT_EQ(face.family(), "Noto Sans Arabic");
  for (const PlacedGlyph& g : shaped.glyphs) ASSERT_EQ(g.face, &face) << "one font sets the whole line";
  EXPECT_EQ(ids_of(shaped), hb_shape(face, "ar", text));
  EXPECT_TRUE(shaped.right_to_left);
  // Joined: heh alone, at a word's end and between two letters takes three forms. The
  // glyphs run right to left: in بهب the middle one is the heh, in به the leftmost.
  const std::uint32_t alone = shaping_font().shape_in("ar", "ه").glyphs.at(0).glyph;
  const ShapedText middle = shaping_font().shape_in("ar", "بهب");
  const ShapedText end = shaping_font().shape_in("ar", "به");
  ASSERT_EQ(middle.glyphs.size(), 3u);
  ASSERT_EQ(end.glyphs.size(), 2u);
  EXPECT_NE(middle.glyphs[1].glyph, alone);
  EXPECT_NE(end.glyphs[0].glyph, alone);
  EXPECT_NE(end.glyphs[0].glyph, middle.glyphs[1].glyph);
}

TEST(TextShaping, DevanagariFormsConjunctsAsHarfBuzzsOwnToolDoes) {
  const std::string text = "क्षेत्र में हिन्दी पट्टी";
  const ShapedText shaped = shaping_font().shape_in("hi", text);
  ASSERT_FALSE(shaped.glyphs.empty());
  const Face& face = *shaped.glyphs.front().face;
  EXPECT_EQ(face.family(), "Noto Sans Devanagari");
  EXPECT_EQ(ids_of(shaped), hb_shape(face, "hi", text));
  EXPECT_FALSE(shaped.right_to_left);
  // The vowel sign ि is written after its consonant and drawn before it: "हि" starts with it.
  const ShapedText hi = shaping_font().shape_in("hi", "हि");
  ASSERT_EQ(hi.glyphs.size(), 2u);
  EXPECT_EQ(hi.glyphs[1].glyph, face.glyph_index(U'\u0939'));
  // क् + ष is one glyph, the conjunct क्ष, not three.
  EXPECT_EQ(shaping_font().shape_in("hi", "क्ष").glyphs.size(), 1u);
}

TEST(TextShaping, HebrewRunsRightToLeftAroundALeftToRightRun) {
  const std::string text = "לחצו Page Down";
  const ShapedText s = shaping_font().shape_in("he", text);
  EXPECT_TRUE(s.right_to_left);
  ASSERT_GE(s.glyphs.size(), 12u);
  // Visual order, left to right: "Page Down" (in its own order), the space, then לחצו reversed.
  const Face& latin = *s.glyphs.front().face;
  EXPECT_EQ(s.glyphs.front().glyph, latin.glyph_index(U'P'));
  const Face& hebrew = *s.glyphs.back().face;
  EXPECT_EQ(hebrew.family(), "Noto Sans Hebrew");
  EXPECT_EQ(s.glyphs.back().glyph, hebrew.glyph_index(U'\u05DC'));  // ל, the first letter, rightmost
  for (std::size_t i = 1; i < s.glyphs.size(); ++i) EXPECT_GE(s.glyphs[i].x, s.glyphs[i - 1].x);
}

TEST(TextShaping, InARightToLeftLanguageATextWithItsLettersRunsRightToLeft) {
  EXPECT_FALSE(shaping_font().shape_in("ar", "settings: /etc/mallet/mallet.toml (2 drop-ins)").right_to_left);
  EXPECT_FALSE(shaping_font().shape_in("ar", "42").right_to_left);
  EXPECT_TRUE(shaping_font().shape_in("ar", "مستوى الصوت 80 %").right_to_left);
  // A translated sentence that starts with a Latin word is still an Arabic sentence.
  const ShapedText title = shaping_font().shape_in("ar", "Mallet: صفحة المشغّل");
  EXPECT_TRUE(title.right_to_left);
  // Read from the right: "Mallet", then the colon to its left, then the Arabic.
  const Face& latin = *title.glyphs.back().face;
  EXPECT_EQ(title.glyphs.back().glyph, latin.glyph_index(U't'));
  const PlacedGlyph& colon = title.glyphs[title.glyphs.size() - 7];
  EXPECT_EQ(colon.glyph, colon.face->glyph_index(U':'));
  EXPECT_FALSE(shaping_font().shape_in("en", "Mallet: صفحة المشغّل").right_to_left);  // the first strong letter's
  EXPECT_TRUE(right_to_left("ar"));
  EXPECT_TRUE(right_to_left("he"));
  EXPECT_FALSE(right_to_left("hi"));
  EXPECT_FALSE(right_to_left("ja"));
}

TEST(TextShaping, JapaneseWithLatinIsSetInOneFont) {
  // The old atlas set the Latin of a Japanese line in another font, so lines looked uneven.
  const ShapedText s = shaping_font().shape_in("ja", "言語：ja  Page Down");
  for (const PlacedGlyph& g : s.glyphs) EXPECT_EQ(g.face->family(), "Noto Sans CJK JP");
}

TEST(TextShaping, LineBreaksFollowTheLanguage) {
  const std::vector<LineBreak> en = line_breaks("one two\nthree", "en");
  ASSERT_EQ(en.size(), 3u);
  EXPECT_EQ(en[0].at, 4u);  // after "one "
  EXPECT_FALSE(en[0].hard);
  EXPECT_EQ(en[1].at, 8u);  // after the newline: a line must end
  EXPECT_TRUE(en[1].hard);
  EXPECT_EQ(en[2].at, 13u);
  EXPECT_TRUE(line_breaks("", "en").empty());
  // A grapheme of several code points (e + combining acute) is never cut.
  EXPECT_EQ(grapheme_ends("e\u0301x"), (std::vector<std::size_t>{3, 4}));
}

}  // namespace
}  // namespace mallet::render
