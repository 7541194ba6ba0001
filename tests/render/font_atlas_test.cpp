// The font atlas: text set by HarfBuzz in fonts fontconfig finds per language, its glyphs
// drawn by FreeType into one atlas on demand and once: real coverage where the glyphs are, no
// two overlapping, a solid texel for shapes; each text set once; a full atlas starts again;
// a letter no font has is named; a bad font file is reported by name.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/file_error.hpp"
#include "render/font_atlas.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

constexpr float kPixelHeight = 32.0f;

bool power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

struct Texels {
  int x0, y0, x1, y1;
};
Texels texels(const FontAtlas& a, const GlyphQuad& q) {
  return {static_cast<int>(std::lround(q.u0 * static_cast<float>(a.width()))),
          static_cast<int>(std::lround(q.v0 * static_cast<float>(a.height()))),
          static_cast<int>(std::lround(q.u1 * static_cast<float>(a.width()))),
          static_cast<int>(std::lround(q.v1 * static_cast<float>(a.height())))};
}

//! The sum of the coverage under a glyph's atlas rectangle.
std::uint64_t ink(const FontAtlas& a, const GlyphQuad& q) {
  const Texels t = texels(a, q);
  std::uint64_t sum = 0;
  for (int y = t.y0; y < t.y1; ++y)
    for (int x = t.x0; x < t.x1; ++x) sum += a.coverage()[static_cast<std::size_t>(y) * a.width() + x];
  return sum;
}

//! Every inked glyph of `text` in `language`, drawn.
std::vector<GlyphQuad> quads(const FontAtlas& a, std::string_view language, std::string_view text) {
  std::vector<GlyphQuad> out;
  for (const PlacedGlyph& g : a.shape_in(language, text).glyphs)
    if (const std::optional<GlyphQuad> q = a.quad(g)) out.push_back(*q);
  return out;
}

TEST(FontAtlas, IsASquarePowerOfTwoThatGrowsWithTheLetters) {
  const FontAtlas small(14.0f), big(90.0f);
  EXPECT_TRUE(power_of_two(small.width()));
  EXPECT_EQ(small.width(), small.height());
  EXPECT_GT(big.width(), small.width());
  EXPECT_EQ(small.coverage().size(), static_cast<std::size_t>(small.width()) * small.height());
}

TEST(FontAtlas, GlyphsAreDrawnWhenFirstNeededAndOnlyOnce) {
  const FontAtlas a(kPixelHeight);
  EXPECT_EQ(a.glyphs_drawn(), 0u);
  const std::uint64_t before = a.generation();
  EXPECT_EQ(quads(a, "en", "Mallet").size(), 6u);
  EXPECT_EQ(a.glyphs_drawn(), 5u);  // M a l e t: the second l is the first's
  const std::uint64_t drawn = a.generation();
  EXPECT_GT(drawn, before);
  quads(a, "en", "Mallet tell");
  EXPECT_EQ(a.glyphs_drawn(), 6u);  // nothing new to draw: the space, known now to have no ink
  EXPECT_EQ(a.generation(), drawn);  // the GPU's copy stays good
}

TEST(FontAtlas, ATextIsSetOnceWhileUnchanged) {
  const FontAtlas a(kPixelHeight);
  a.measure("Pick up the mallet");
  const std::uint64_t once = a.shapings();
  a.measure("Pick up the mallet");
  a.shape_in("en", "Pick up the mallet");
  EXPECT_EQ(a.shapings(), once);
  a.shape_in("de", "Pick up the mallet");  // another language sets it anew (its fonts, its rules)
  EXPECT_EQ(a.shapings(), once + 1);
}

TEST(FontAtlas, EveryGlyphLiesInsideTheAtlasAndNoTwoOverlap) {
  const FontAtlas a(kPixelHeight);
  std::vector<Texels> all;
  for (const auto& [language, text] : std::vector<std::pair<std::string, std::string>>{
           {"en", "Pick up the mallet and strike a bar"}, {"ja", "マレットを持って、鍵盤をたたいてみよう"},
           {"ar", "ارفع المطرقة واضرب أحد القضبان"}, {"hi", "हथौड़ी उठाएँ और किसी पट्टी पर मारें"},
           {"ko", "채를 들고 건반을 쳐 보세요"}, {"he", "הרימו את המקוש"}}) {
    for (const GlyphQuad& q : quads(a, language, text)) {
      EXPECT_GE(q.u0, 0.0f);
      EXPECT_LE(q.u1, 1.0f);
      EXPECT_GE(q.v0, 0.0f);
      EXPECT_LE(q.v1, 1.0f);
      EXPECT_GT(ink(a, q), 0u) << language;  // real coverage where the glyph is
      all.push_back(texels(a, q));
    }
  }
  std::sort(all.begin(), all.end(), [](const Texels& l, const Texels& r) { return std::tie(l.x0, l.y0) < std::tie(r.x0, r.y0); });
  all.erase(std::unique(all.begin(), all.end(), [](const Texels& l, const Texels& r) {
              return l.x0 == r.x0 && l.y0 == r.y0 && l.x1 == r.x1 && l.y1 == r.y1;
            }), all.end());  // a glyph used twice is one rectangle
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_TRUE(all[i].y0 >= 4 || all[i].x0 >= 4) << "a glyph over the solid block";
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const bool apart = all[i].x1 <= all[j].x0 || all[j].x1 <= all[i].x0 || all[i].y1 <= all[j].y0 ||
                         all[j].y1 <= all[i].y0;
      EXPECT_TRUE(apart) << "glyphs " << i << " and " << j << " overlap";
    }
  }
  EXPECT_GT(all.size(), 60u);
}

TEST(FontAtlas, TheSolidTexelIsFullyCovered) {
  const FontAtlas a(kPixelHeight);
  quads(a, "en", "Wood");
  const int x = static_cast<int>(a.solid_u() * static_cast<float>(a.width()));
  const int y = static_cast<int>(a.solid_v() * static_cast<float>(a.height()));
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      EXPECT_EQ(a.coverage()[static_cast<std::size_t>(y + dy) * a.width() + x + dx], 255);
}

TEST(FontAtlas, CapitalsStandAsTheLayoutsExpect) {
  const FontAtlas a(kPixelHeight);
  const std::vector<GlyphQuad> h = quads(a, "en", "H");
  ASSERT_EQ(h.size(), 1u);
  const float capital = h[0].y1 - h[0].y0;
  EXPECT_NEAR(capital / kPixelHeight, 0.625f, 0.04f);  // as the kiosk's text always stood
  EXPECT_NEAR(h[0].y1, 0.0f, 1.0f);                   // on the baseline
  EXPECT_GT(a.ascent(), capital);
  EXPECT_GT(a.descent(), 0.0f);
}

TEST(FontAtlas, WideLettersAreWiderAndPairsKern) {
  const FontAtlas a(kPixelHeight);
  EXPECT_GT(a.measure("W"), a.measure("i"));
  EXPECT_LT(a.measure("AV"), a.measure("A") + a.measure("V"));  // the font's kerning, by HarfBuzz
}

TEST(FontAtlas, EachLanguageStartsWithItsScriptsNotoFamily) {
  const FontAtlas a(kPixelHeight);
  EXPECT_EQ(a.fonts("en").faces().front()->family(), "Noto Sans");
  EXPECT_EQ(a.fonts("ja").faces().front()->family(), "Noto Sans CJK JP");
  EXPECT_EQ(a.fonts("zh").faces().front()->family(), "Noto Sans CJK SC");
  EXPECT_EQ(a.fonts("ko").faces().front()->family(), "Noto Sans CJK KR");
  EXPECT_EQ(a.fonts("ar").faces().front()->family(), "Noto Sans Arabic");
  EXPECT_EQ(a.fonts("he").faces().front()->family(), "Noto Sans Hebrew");
  EXPECT_EQ(a.fonts("hi").faces().front()->family(), "Noto Sans Devanagari");
  // Latin in a Devanagari line comes from the language's next font, found by fontconfig.
  EXPECT_TRUE(a.has_in("hi", U'R'));
  EXPECT_TRUE(a.has_in("ar", U'%'));
}

TEST(FontAtlas, AnOperatorsFamilyComesFirstAndAnUnknownOneFallsBack) {
  FontChoice choice;
  choice.families["en"] = "Noto Serif";
  choice.families["de"] = "No Such Family Anywhere";
  const FontAtlas a(kPixelHeight, choice);
  EXPECT_EQ(a.fonts("en").faces().front()->family(), "Noto Serif");
  EXPECT_TRUE(a.has_in("de", U'ß'));  // fontconfig's next best
  EXPECT_GT(a.measure("Schlägel"), 0.0f);
}

TEST(FontAtlas, LettersNoFontHasAreNamedOnce) {
  const FontAtlas a(kPixelHeight);
  // U+E000 is private use: no font of Debian's has it.
  EXPECT_EQ(a.missing_letters("en", "a\uE000b\uE000 \uE001", 8), (std::vector<std::string>{"\uE000", "\uE001"}));
  EXPECT_TRUE(a.missing_letters("ja", "マレットを持って", 8).empty());
  EXPECT_TRUE(a.missing_letters("ar", "ارفع المطرقة", 8).empty());
  EXPECT_FALSE(a.shape_in("en", "\uE000").complete);
  EXPECT_TRUE(a.shape_in("en", "Mallet").complete);
}

TEST(FontAtlas, MalformedUtf8IsSetAsReplacementCharacters) {
  const FontAtlas a(kPixelHeight);
  EXPECT_EQ(a.shape_in("en", "\xff\xfe").glyphs.size(), 2u);
  EXPECT_FLOAT_EQ(a.measure("\xC3" "a"), a.measure("\uFFFD" "a"));  // cut short before a letter
  EXPECT_EQ(a.measure(""), 0.0f);
}

TEST(FontAtlas, AFullAtlasStartsAgainAndDrawsOn) {
  const FontAtlas a(14.0f);
  // Thousands of ideographs: more than a 14 px atlas holds.
  std::string text;
  for (char32_t c = 0x4E00; c < 0x4E00 + 8000; ++c) {
    text += static_cast<char>(0xE0 | (c >> 12));
    text += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    text += static_cast<char>(0x80 | (c & 0x3F));
  }
  const std::uint64_t before = a.generation();
  const std::vector<GlyphQuad> drawn = quads(a, "zh", text);
  EXPECT_GT(drawn.size(), 7900u);
  EXPECT_LT(a.glyphs_drawn(), 7000u);  // it started again on the way
  EXPECT_GT(a.generation(), before + a.glyphs_drawn());
  const std::vector<GlyphQuad> after = quads(a, "en", "Mallet");  // and goes on drawing
  ASSERT_EQ(after.size(), 6u);
  for (const GlyphQuad& q : after) EXPECT_GT(ink(a, q), 0u);
}

TEST(FontAtlasUtf8, DecodesWellFormedText) {
  EXPECT_EQ(decode_utf8("Mallet"), U"Mallet");
  EXPECT_EQ(decode_utf8("caf\xC3\xA9"), U"caf\u00E9");
  EXPECT_EQ(decode_utf8("\xE2\x82\xAC"), U"\u20AC");
  EXPECT_EQ(decode_utf8("\xF0\x9F\x98\x80"), U"\U0001F600");
  EXPECT_EQ(decode_utf8("\xF4\x8F\xBF\xBF"), U"\U0010FFFF");
}

TEST(FontAtlasUtf8, EachBrokenSequenceBecomesOneReplacementCharacter) {
  EXPECT_EQ(decode_utf8("\x80"), U"\uFFFD");
  EXPECT_EQ(decode_utf8("\xF0\x9F\x98" "A"), U"\uFFFD" "A");      // one for the truncated run
  EXPECT_EQ(decode_utf8("\xE0\x80\x80"), U"\uFFFD\uFFFD\uFFFD");  // overlong: no valid start
  EXPECT_EQ(decode_utf8("\xF4\x90\x80\x80"), U"\uFFFD\uFFFD\uFFFD\uFFFD");  // > U+10FFFF
  EXPECT_EQ(decode_utf8("\xF8\x88\x80\x80\x80"), U"\uFFFD\uFFFD\uFFFD\uFFFD\uFFFD");
  EXPECT_EQ(decode_utf8("a\xC3"), U"a\uFFFD");
}

TEST(FontFace, ABadFontFileIsReportedByName) {
  const auto dir = test::scratch_dir();
  {
    std::ofstream(dir / "garbage.ttf") << "this is not a font";
    std::ofstream(dir / "empty.ttf");
  }
  for (const char* name : {"garbage.ttf", "empty.ttf", "absent.ttf"}) {
    const FileError e = test::file_error_of([&] { Face(dir / name, 0, 20.0f); });
    EXPECT_EQ(e.file(), (dir / name).string());
  }
}

TEST(FontAtlas, AnUnusablePixelHeightIsRefused) {
  EXPECT_THROW(FontAtlas(0.0f), std::invalid_argument);
  EXPECT_THROW(FontAtlas(-12.0f), std::invalid_argument);
  EXPECT_THROW(FontAtlas(std::numeric_limits<float>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(FontAtlas(300.0f), std::invalid_argument);
}

}  // namespace
}  // namespace mallet::render
