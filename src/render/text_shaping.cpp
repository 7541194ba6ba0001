#include "render/text_shaping.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <hb.h>
#include <unicode/brkiter.h>
#include <unicode/locid.h>
#include <unicode/ubidi.h>
#include <unicode/uchar.h>
#include <unicode/uloc.h>
#include <unicode/unistr.h>
#include <unicode/utf8.h>

namespace mallet::render {
namespace {

//! The text in UTF-16 (what ICU and hb_buffer_add_utf16 take) and, for each of its code
//! units and one past the end, the byte offset in the UTF-8 it came from. Malformed UTF-8
//! becomes U+FFFD, one per maximal ill-formed subsequence (ICU's U8_NEXT_OR_FFFD).
struct Utf16Text {
  icu::UnicodeString text;
  std::vector<std::size_t> byte_at;
};

Utf16Text to_utf16(std::string_view utf8) {
  Utf16Text out;
  const auto* s = reinterpret_cast<const std::uint8_t*>(utf8.data());
  const auto length = static_cast<std::int32_t>(utf8.size());
  for (std::int32_t i = 0; i < length;) {
    const std::int32_t start = i;
    UChar32 c = 0;
    U8_NEXT_OR_FFFD(s, i, length, c);
    out.text.append(c);
    const std::size_t units = U16_LENGTH(c);
    for (std::size_t u = 0; u < units; ++u) out.byte_at.push_back(static_cast<std::size_t>(start));
  }
  out.byte_at.push_back(utf8.size());
  return out;
}

//! A letter that belongs with the one before it, whatever font that took: a combining mark,
//! a joiner, a variation selector.
bool clings(UChar32 c) {
  const auto category = static_cast<UCharCategory>(u_charType(c));
  return category == U_NON_SPACING_MARK || category == U_ENCLOSING_MARK || category == U_COMBINING_SPACING_MARK ||
         c == 0x200C || c == 0x200D || u_hasBinaryProperty(c, UCHAR_VARIATION_SELECTOR);
}

//! One piece of a run set in one font: [start, end) in UTF-16 units.
struct Piece {
  std::int32_t start = 0, end = 0;
  int face = 0;
};

//! A run's pieces in logical order: each letter in the font it is in, trying first the font
//! the piece so far is set in (a line stays in one font where that font can), then the
//! language's fonts in order. A letter no font has stays in the piece's font (its box).
std::vector<Piece> pieces_of(const FontFallback& fonts, const icu::UnicodeString& text, std::int32_t start,
                             std::int32_t end, bool& complete) {
  std::vector<Piece> pieces;
  for (std::int32_t i = start; i < end;) {
    const std::int32_t at = i;
    const UChar32 c = text.char32At(i);
    i += U16_LENGTH(c);
    const auto& faces = fonts.faces();
    if (!pieces.empty() && (clings(c) || faces[static_cast<std::size_t>(pieces.back().face)]->has(c))) {
      pieces.back().end = i;
      continue;
    }
    int face = fonts.face_for(c);
    if (face < 0) {
      if (!u_isWhitespace(c) && !u_hasBinaryProperty(c, UCHAR_DEFAULT_IGNORABLE_CODE_POINT)) complete = false;
      if (!pieces.empty()) {
        pieces.back().end = i;
        continue;
      }
      face = 0;
    }
    if (!pieces.empty() && pieces.back().face == face)
      pieces.back().end = i;
    else
      pieces.push_back({at, i, face});
  }
  return pieces;
}

struct BidiDeleter {
  void operator()(UBiDi* b) const { ubidi_close(b); }
};

}  // namespace

bool right_to_left(std::string_view language) {
  return uloc_isRightToLeft(std::string(language).c_str()) != 0;
}

ShapedText shape_text(const FontFallback& fonts, std::string_view utf8) {
  ShapedText out;
  const Utf16Text u = to_utf16(utf8);
  const std::int32_t length = u.text.length();
  if (length == 0) return out;
  UErrorCode status = U_ZERO_ERROR;
  const std::unique_ptr<UBiDi, BidiDeleter> bidi(ubidi_openSized(length, 0, &status));
  // A right-to-left language's text runs right to left wherever it has a right-to-left letter
  // (a translated "Mallet: صفحة المشغّل" starts with a Latin word but is an Arabic sentence);
  // one without any (a file's path, an English status line) runs left to right, so that its
  // brackets and full stop stay where English puts them. Another language's text takes its
  // first strong letter's direction (UAX #9's default).
  UBiDiLevel paragraph = UBIDI_DEFAULT_LTR;
  if (right_to_left(fonts.language())) {
    paragraph = UBIDI_LTR;
    for (std::int32_t i = 0; i < length;) {
      const UChar32 c = u.text.char32At(i);
      i += U16_LENGTH(c);
      const UCharDirection d = u_charDirection(c);
      if (d == U_RIGHT_TO_LEFT || d == U_RIGHT_TO_LEFT_ARABIC) {
        paragraph = UBIDI_RTL;
        break;
      }
    }
  }
  ubidi_setPara(bidi.get(), u.text.getBuffer(), length, paragraph, nullptr, &status);
  const std::int32_t runs = U_SUCCESS(status) ? ubidi_countRuns(bidi.get(), &status) : 0;
  out.right_to_left = U_SUCCESS(status) ? (ubidi_getParaLevel(bidi.get()) & 1) != 0 : false;
  const hb_language_t language = hb_language_from_string(fonts.language().c_str(), -1);
  hb_buffer_t* buffer = hb_buffer_create();
  float pen = 0;
  auto set_piece = [&](const Piece& piece, bool rtl) {
    const Face& face = *fonts.faces()[static_cast<std::size_t>(piece.face)];
    hb_buffer_clear_contents(buffer);
    // The whole text as context: a piece's first and last letters join (or not) as in the line.
    hb_buffer_add_utf16(buffer, reinterpret_cast<const std::uint16_t*>(u.text.getBuffer()), length,
                        static_cast<unsigned>(piece.start), static_cast<int>(piece.end - piece.start));
    hb_buffer_set_direction(buffer, rtl ? HB_DIRECTION_RTL : HB_DIRECTION_LTR);
    hb_buffer_set_language(buffer, language);
    hb_buffer_guess_segment_properties(buffer);  // the script, from the letters
    hb_shape(face.hb(), buffer, nullptr, 0);
    unsigned count = 0;
    const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
    const hb_glyph_position_t* pos = hb_buffer_get_glyph_positions(buffer, &count);
    for (unsigned g = 0; g < count; ++g) {  // HarfBuzz gives them in visual order
      out.glyphs.push_back({&face, info[g].codepoint, pen + static_cast<float>(pos[g].x_offset) / 64.0f,
                            -static_cast<float>(pos[g].y_offset) / 64.0f});
      pen += static_cast<float>(pos[g].x_advance) / 64.0f;
    }
  };
  for (std::int32_t r = 0; r < runs; ++r) {
    std::int32_t start = 0, run_length = 0;
    const bool rtl = ubidi_getVisualRun(bidi.get(), r, &start, &run_length) == UBIDI_RTL;
    std::vector<Piece> pieces = pieces_of(fonts, u.text, start, start + run_length, out.complete);
    if (rtl) std::reverse(pieces.begin(), pieces.end());  // a right-to-left run's last piece is leftmost
    for (const Piece& p : pieces) set_piece(p, rtl);
  }
  hb_buffer_destroy(buffer);
  out.width = pen;
  return out;
}

namespace {

//! ICU's break iterators, made once per locale (making one reads its rules) and used by the
//! thread that draws; a mutex keeps another thread's use safe.
std::mutex iterators_mutex;

//! Null only if ICU has no line rules at all (its data missing).
icu::BreakIterator* line_iterator(std::string_view language, bool phrases) {
  static std::map<std::string, std::unique_ptr<icu::BreakIterator>, std::less<>> made;
  // Japanese breaks between phrases (ICU's "lw=phrase"), not between any two ideographs:
  // a word such as 言語 is never split across lines.
  const std::string locale = language == "ja" && phrases ? "ja@lw=phrase" : std::string(language);
  auto it = made.find(locale);
  if (it == made.end()) {
    UErrorCode status = U_ZERO_ERROR;
    std::unique_ptr<icu::BreakIterator> made_one(
        icu::BreakIterator::createLineInstance(icu::Locale::createCanonical(locale.c_str()), status));
    if (U_FAILURE(status) || !made_one) {
      status = U_ZERO_ERROR;
      made_one.reset(icu::BreakIterator::createLineInstance(icu::Locale::getRoot(), status));
    }
    it = made.emplace(locale, std::move(made_one)).first;
  }
  return it->second.get();
}

}  // namespace

std::vector<LineBreak> line_breaks(std::string_view utf8, std::string_view language, bool phrases) {
  std::vector<LineBreak> out;
  if (utf8.empty()) return out;
  const Utf16Text u = to_utf16(utf8);
  const std::lock_guard lock(iterators_mutex);
  icu::BreakIterator* it = line_iterator(language, phrases);
  if (!it) return {{utf8.size(), false}};
  it->setText(u.text);
  it->first();
  // A script written without spaces: its letters' line-break classes (ideographs, kana,
  // Thai and its neighbours' dictionary words).
  auto spaceless = [](UChar32 c) {
    const auto lb = static_cast<ULineBreak>(u_getIntPropertyValue(c, UCHAR_LINE_BREAK));
    return lb == U_LB_IDEOGRAPHIC || lb == U_LB_CONDITIONAL_JAPANESE_STARTER || lb == U_LB_COMPLEX_CONTEXT;
  };
  const std::int32_t length = u.text.length();
  for (std::int32_t b = it->next(); b != icu::BreakIterator::DONE; b = it->next()) {
    const std::int32_t status = it->getRuleStatus();
    LineBreak lb{u.byte_at[static_cast<std::size_t>(b)], status >= UBRK_LINE_HARD && status < UBRK_LINE_HARD_LIMIT};
    if (!lb.hard && b > 0 && b < length) {
      const UChar32 before = u.text.char32At(u.text.moveIndex32(b, -1)), after = u.text.char32At(b);
      lb.in_word = !u_isWhitespace(before) && !spaceless(before) && !spaceless(after);
    }
    out.push_back(lb);
  }
  if (out.empty() || out.back().at != utf8.size()) out.push_back({utf8.size(), false});
  return out;
}

std::vector<std::size_t> grapheme_ends(std::string_view utf8) {
  std::vector<std::size_t> out;
  if (utf8.empty()) return out;
  const Utf16Text u = to_utf16(utf8);
  const std::lock_guard lock(iterators_mutex);
  static std::unique_ptr<icu::BreakIterator> characters = [] {
    UErrorCode status = U_ZERO_ERROR;
    return std::unique_ptr<icu::BreakIterator>(icu::BreakIterator::createCharacterInstance(icu::Locale::getRoot(), status));
  }();
  if (!characters) {
    for (std::size_t i = 1; i < u.byte_at.size(); ++i)
      if (out.empty() || u.byte_at[i] != out.back()) out.push_back(u.byte_at[i]);
    return out;
  }
  characters->setText(u.text);
  characters->first();
  for (std::int32_t b = characters->next(); b != icu::BreakIterator::DONE; b = characters->next())
    out.push_back(u.byte_at[static_cast<std::size_t>(b)]);
  return out;
}

}  // namespace mallet::render
