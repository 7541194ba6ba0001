// The font atlas: DejaVu Sans baked at one size holds every Latin-1 glyph in a power-of-two
// atlas, with real coverage, real metrics and the font's kerning; a solid texel for shapes;
// broken UTF-8 and unknown code points draw as '?'; a bad font file is reported by name; the
// glyphs of a text in another script (Japanese) come from a second font into the same atlas.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/file_error.hpp"
#include "render/font_atlas.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

constexpr float kPixelHeight = 32.0f;

const FontAtlas& atlas() {
  static const FontAtlas baked(FontAtlas::default_font(), kPixelHeight);
  return baked;
}

bool power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

//! The sum of the coverage under a glyph's atlas rectangle.
std::uint64_t ink(const FontAtlas& a, const GlyphQuad& q) {
  const int x0 = static_cast<int>(std::lround(q.u0 * static_cast<float>(a.width())));
  const int x1 = static_cast<int>(std::lround(q.u1 * static_cast<float>(a.width())));
  const int y0 = static_cast<int>(std::lround(q.v0 * static_cast<float>(a.height())));
  const int y1 = static_cast<int>(std::lround(q.v1 * static_cast<float>(a.height())));
  std::uint64_t sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += a.coverage()[static_cast<std::size_t>(y) * a.width() + x];
  return sum;
}

bool same_quad(const GlyphQuad& a, const GlyphQuad& b) {
  return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1 && a.u0 == b.u0 && a.v0 == b.v0 &&
         a.u1 == b.u1 && a.v1 == b.v1 && a.advance == b.advance;
}

TEST(FontAtlas, IsAPowerOfTwoSquareOrTwoToOne) {
  const FontAtlas& a = atlas();
  EXPECT_TRUE(power_of_two(a.width())) << a.width();
  EXPECT_TRUE(power_of_two(a.height())) << a.height();
  EXPECT_TRUE(a.width() == a.height() || a.width() == 2 * a.height()) << a.width() << "x" << a.height();
  EXPECT_EQ(a.coverage().size(), static_cast<std::size_t>(a.width()) * a.height());
  EXPECT_EQ(a.pixel_height(), kPixelHeight);
}

TEST(FontAtlas, EveryGlyphLiesInsideTheAtlasAndNoTwoOverlap) {
  const FontAtlas& a = atlas();
  const float w = static_cast<float>(a.width()), h = static_cast<float>(a.height());
  for (char32_t cp = 0x20; cp <= 0xFF; ++cp) {
    const GlyphQuad q = a.glyph(cp);
    SCOPED_TRACE(testing::Message() << "U+" << std::hex << static_cast<unsigned>(cp));
    EXPECT_GE(q.u0, 0.0f);
    EXPECT_LE(q.u1, 1.0f);
    EXPECT_GE(q.v0 * h, 4.0f);  // below the solid block's rows
    EXPECT_LE(q.v1, 1.0f);
    EXPECT_LE(q.u0, q.u1);
    EXPECT_LE(q.v0, q.v1);
    // One screen pixel per atlas texel vertically, two horizontally (2× oversampling).
    EXPECT_NEAR((q.v1 - q.v0) * h, q.y1 - q.y0, 1e-3);
    EXPECT_NEAR((q.u1 - q.u0) * w, 2 * (q.x1 - q.x0), 1e-3);
  }
  for (char32_t a1 = U'A'; a1 <= U'Z'; ++a1)
    for (char32_t b1 = a1 + 1; b1 <= U'Z'; ++b1) {
      const GlyphQuad p = a.glyph(a1), q = a.glyph(b1);
      const bool apart = p.u1 <= q.u0 || q.u1 <= p.u0 || p.v1 <= q.v0 || q.v1 <= p.v0;
      EXPECT_TRUE(apart) << static_cast<char>(a1) << " and " << static_cast<char>(b1) << " overlap";
    }
}

TEST(FontAtlas, VerticalMetricsSpanThePixelHeight) {
  const FontAtlas& a = atlas();
  EXPECT_GT(a.ascent(), a.descent());
  EXPECT_GT(a.descent(), 0.0f);
  EXPECT_GE(a.line_gap(), 0.0f);
  EXPECT_NEAR(a.ascent() + a.descent(), kPixelHeight, 1e-3);
}

TEST(FontAtlas, GlyphsSitOnTheBaseline) {
  const FontAtlas& a = atlas();
  const GlyphQuad cap = a.glyph(U'A');
  EXPECT_LT(cap.y0, -0.5f * kPixelHeight);  // a capital rises well above the baseline...
  EXPECT_GE(cap.y0, -a.ascent() - 1);        // ...but not above the ascent
  EXPECT_NEAR(cap.y1, 0.0f, 1.0f);           // and stands on it
  EXPECT_GT(a.glyph(U'g').y1, 2.0f);         // a descender goes below
}

TEST(FontAtlas, WideLettersAreWiderThanNarrowOnes) {
  const FontAtlas& a = atlas();
  EXPECT_GT(a.glyph(U'M').advance, 1.5f * a.glyph(U'i').advance);
  EXPECT_GT(a.glyph(U'M').x1 - a.glyph(U'M').x0, 2 * (a.glyph(U'i').x1 - a.glyph(U'i').x0));
  EXPECT_GT(a.measure("MMMM"), a.measure("iiii"));
}

TEST(FontAtlas, InkIsWhereTheGlyphsAre) {
  const FontAtlas& a = atlas();
  EXPECT_GT(ink(a, a.glyph(U'A')), 255u * 20);
  const GlyphQuad space = a.glyph(U' ');
  EXPECT_EQ(ink(a, space), 0u);
  EXPECT_TRUE(space.x1 <= space.x0 || space.y1 <= space.y0);  // nothing to draw...
  EXPECT_GT(space.advance, 0.0f);                              // ...but it moves the pen
}

TEST(FontAtlas, TheSolidTexelIsFullyCovered) {
  const FontAtlas& a = atlas();
  const float tx = a.solid_u() * static_cast<float>(a.width());
  const float ty = a.solid_v() * static_cast<float>(a.height());
  EXPECT_FLOAT_EQ(tx - std::floor(tx), 0.5f);  // a texel's centre: bilinear reads it alone
  EXPECT_FLOAT_EQ(ty - std::floor(ty), 0.5f);
  const int x = static_cast<int>(tx), y = static_cast<int>(ty);
  for (int dy = -1; dy <= 1; ++dy)  // and its neighbours, for a uv a hair off
    for (int dx = -1; dx <= 1; ++dx)
      EXPECT_EQ(a.coverage()[static_cast<std::size_t>(y + dy) * a.width() + x + dx], 255);
}

TEST(FontAtlas, KerningTightensPairsLikeAV) {
  const FontAtlas& a = atlas();
  EXPECT_LT(a.kerning(U'A', U'V'), -0.5f);  // DejaVu Sans kerns A-V by about 2 px at 32 px
  EXPECT_LT(a.measure("AV"), a.measure("A") + a.measure("V"));
  EXPECT_NEAR(a.measure("AV"), a.measure("A") + a.measure("V") + a.kerning(U'A', U'V'), 1e-4);
  EXPECT_EQ(a.kerning(U'H', U'H'), 0.0f);
}

TEST(FontAtlas, LatinOneLettersAreBaked) {
  const FontAtlas& a = atlas();
  const GlyphQuad e_acute = a.glyph(U'\u00E9');
  EXPECT_FALSE(same_quad(e_acute, a.glyph(U'?')));
  EXPECT_GT(ink(a, e_acute), 255u * 10);
  EXPECT_LT(e_acute.y0, a.glyph(U'e').y0 - 2);  // the accent stands above the e
  EXPECT_FLOAT_EQ(a.measure("\xC3\xA9"), e_acute.advance);  // "é" in UTF-8
  EXPECT_FALSE(same_quad(a.glyph(U'\u00FF'), a.glyph(U'?')));  // ÿ, the last one
}

TEST(FontAtlas, CodePointsOutsideTheRangeDrawAsQuestionMarks) {
  const FontAtlas& a = atlas();
  const GlyphQuad question = a.glyph(U'?');
  EXPECT_TRUE(same_quad(a.glyph(U'\u20AC'), question));  // €
  EXPECT_TRUE(same_quad(a.glyph(U'\n'), question));
  EXPECT_TRUE(same_quad(a.glyph(U'\U0001F600'), question));
  EXPECT_TRUE(same_quad(a.glyph(0x110000), question));
  EXPECT_FLOAT_EQ(a.measure("\xE2\x82\xAC"), a.measure("?"));
}

TEST(FontAtlas, InvalidUtf8MeasuresLikeQuestionMarks) {
  const FontAtlas& a = atlas();
  EXPECT_FLOAT_EQ(a.measure("\xFF"), a.measure("?"));
  EXPECT_FLOAT_EQ(a.measure("a\xC3"), a.measure("a?"));          // cut short at the end
  EXPECT_FLOAT_EQ(a.measure("\xC3" "a"), a.measure("?a"));       // cut short before a letter
  EXPECT_FLOAT_EQ(a.measure("\xC0\xAF"), a.measure("??"));       // overlong '/'
  EXPECT_FLOAT_EQ(a.measure("\xED\xA0\x80"), a.measure("???"));  // a UTF-16 surrogate
  EXPECT_FLOAT_EQ(a.measure(std::string_view("\0", 1)), a.measure("?"));
  EXPECT_EQ(a.measure(""), 0.0f);
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

TEST(FontAtlas, CopiesOutliveTheOriginal) {
  auto original = std::make_unique<FontAtlas>(FontAtlas::default_font(), 18.0f);
  const float av = original->measure("AVATAR");
  const FontAtlas copy = *original;
  original.reset();
  EXPECT_EQ(copy.measure("AVATAR"), av);  // kerning reads the shared font file
}

TEST(FontAtlas, AMissingFontIsReportedByName) {
  const auto file = test::scratch_dir() / "absent.ttf";
  const FileError e = test::file_error_of([&] { FontAtlas(file, 20.0f); });
  EXPECT_EQ(e.file(), file.string());
  EXPECT_NE(std::string(e.what()).find("no such font file"), std::string::npos) << e.what();
}

TEST(FontAtlas, GarbageAndTruncatedFontsAreReportedByName) {
  const auto dir = test::scratch_dir();
  {
    std::ofstream out(dir / "garbage.ttf", std::ios::binary);
    out << "definitely not a TrueType font, just some text long enough";
  }
  const FileError garbage = test::file_error_of([&] { FontAtlas(dir / "garbage.ttf", 20.0f); });
  EXPECT_EQ(garbage.file(), (dir / "garbage.ttf").string());

  // The real font's first kilobyte: a valid header whose tables run past the end.
  std::ifstream in(FontAtlas::default_font(), std::ios::binary);
  std::string head(1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  {
    std::ofstream out(dir / "cut.ttf", std::ios::binary);
    out << head;
  }
  const FileError cut = test::file_error_of([&] { FontAtlas(dir / "cut.ttf", 20.0f); });
  EXPECT_EQ(cut.file(), (dir / "cut.ttf").string());
  EXPECT_NE(std::string(cut.what()).find("not a usable TrueType font"), std::string::npos) << cut.what();

  { std::ofstream out(dir / "empty.ttf"); }
  EXPECT_EQ(test::file_error_of([&] { FontAtlas(dir / "empty.ttf", 20.0f); }).file(), (dir / "empty.ttf").string());
}

TEST(FontAtlas, AnUnusablePixelHeightIsRefused) {
  EXPECT_THROW(FontAtlas(FontAtlas::default_font(), 0.0f), std::invalid_argument);
  EXPECT_THROW(FontAtlas(FontAtlas::default_font(), -12.0f), std::invalid_argument);
  EXPECT_THROW(FontAtlas(FontAtlas::default_font(), std::numeric_limits<float>::quiet_NaN()),
               std::invalid_argument);
}

TEST(FontAtlas, BiggerTextNeedsABiggerAtlas) {
  const FontAtlas small(FontAtlas::default_font(), 12.0f);
  const FontAtlas big(FontAtlas::default_font(), 64.0f);
  EXPECT_LT(static_cast<long>(small.width()) * small.height(), static_cast<long>(big.width()) * big.height());
  EXPECT_NEAR(big.measure("Mallet") / small.measure("Mallet"), 64.0 / 12.0, 0.15);
}

// ---- the visitor languages' other scripts: extra code points, from a second font ----

TEST(FontAtlas, TextBeyondLatinOneIsBakedFromTheMainFontOrTheSecond) {
  // "€" is DejaVu's own; the kana and kanji are IPAGothic's (fonts-ipafont-gothic).
  const FontAtlas a(FontAtlas::default_font(), kPixelHeight, "Tap €  マレット鍵盤", FontAtlas::default_cjk_font());
  for (const char32_t cp : {U'\u20AC', U'マ', U'レ', U'ッ', U'ト', U'鍵', U'盤'}) {
    EXPECT_TRUE(a.has(cp)) << static_cast<unsigned>(cp);
    const GlyphQuad q = a.glyph(cp);
    EXPECT_FALSE(same_quad(q, a.glyph(U'?'))) << static_cast<unsigned>(cp);
    EXPECT_GT(ink(a, q), 0u) << static_cast<unsigned>(cp);
    EXPECT_GE(q.u0, 0.0f);
    EXPECT_LE(q.u1, 1.0f);
    EXPECT_LE(q.v1, 1.0f);
  }
  EXPECT_FALSE(a.has(U'猫'));  // not in the text: not baked
  EXPECT_TRUE(same_quad(a.glyph(U'猫'), a.glyph(U'?')));
  // A full-width kanji is about a pixel height wide; Latin-1 is as before.
  EXPECT_NEAR(a.glyph(U'鍵').advance, kPixelHeight, kPixelHeight * 0.2f);
  EXPECT_FLOAT_EQ(a.measure("AV"), atlas().measure("AV"));  // kerning kept
}

TEST(FontAtlas, WithoutASecondFontTheOtherScriptsDrawAsQuestionMarks) {
  const FontAtlas a(FontAtlas::default_font(), kPixelHeight, "マレット", {});
  EXPECT_FALSE(a.has(U'マ'));
  EXPECT_TRUE(same_quad(a.glyph(U'マ'), a.glyph(U'?')));
  EXPECT_EQ(a.width(), atlas().width());
}

TEST(FontAtlas, AMissingSecondFontIsReportedByName) {
  const FontAtlas latin(FontAtlas::default_font(), kPixelHeight, "only Latin-1: é", "/no/such/cjk.ttf");
  EXPECT_TRUE(latin.has(U'é'));  // not needed, not opened
  const FileError e =
      test::file_error_of([] { FontAtlas(FontAtlas::default_font(), kPixelHeight, "マ", "/no/such/cjk.ttf"); });
  EXPECT_EQ(e.file(), "/no/such/cjk.ttf");
  EXPECT_NE(std::string(e.what()).find("fonts-ipafont-gothic"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace mallet::render
