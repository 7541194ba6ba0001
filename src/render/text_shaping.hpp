#pragma once
// A line of text set as the desktop sets it: Unicode's bidirectional algorithm (UAX #9, ICU's
// ubidi) puts right-to-left runs (Arabic, Hebrew) in visual order; each run goes, a piece
// per font of the language's fallback (render/font_fallback.hpp), to HarfBuzz, which picks
// the glyphs (Arabic's joined forms, Devanagari's conjuncts and reordered vowel signs) and
// places them. Where a line may end is Unicode line breaking (UAX #14, ICU's line
// BreakIterator; Japanese by phrases, Thai by its dictionary).
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "render/font_fallback.hpp"

namespace mallet::render {

//! One glyph of a set line: which font's, which glyph, and where its origin lies relative to
//! the line's start on its baseline (pixels, x right, y down).
struct PlacedGlyph {
  const Face* face = nullptr;
  std::uint32_t glyph = 0;
  float x = 0, y = 0;
};

struct ShapedText {
  std::vector<PlacedGlyph> glyphs;  //!< in visual order, left to right
  float width = 0;                  //!< the pen's advance over the whole line, pixels
  //! The paragraph's direction: in a right-to-left language, whether the text has any
  //! right-to-left letter; in another, its first strong letter's (UAX #9).
  bool right_to_left = false;
  bool complete = true;             //!< every letter had a font (false: some draw as the font's empty box)
};

//! `utf8` set in `fonts` (its language's). Malformed UTF-8 sets as U+FFFD.
ShapedText shape_text(const FontFallback& fonts, std::string_view utf8);

//! Whether `language` is written right to left (ar, he, fa, ...): its lines are aligned right,
//! and a text with its letters runs right to left.
bool right_to_left(std::string_view language);

struct LineBreak {
  std::size_t at = 0;  //!< byte offset in the text where a line may end (and the next begin)
  bool hard = false;   //!< a line must end here (a newline)
  //! Inside a word of a language written with spaces (after the / or - of a path, between
  //! two Hangul syllables): a place to break only a word too wide for a line. A break after a
  //! space, or beside an ideograph or a Thai letter (scripts written without spaces), is not.
  bool in_word = false;
};
//! Where lines of `utf8` may end, in `language`'s rules, in order; the text's end last. An
//! empty text has none. Japanese by phrases; `phrases` false: between any two characters
//! UAX #14 allows (for a phrase wider than a line).
std::vector<LineBreak> line_breaks(std::string_view utf8, std::string_view language, bool phrases = true);

//! Byte offsets where each user-perceived character (grapheme cluster) ends, in order: the
//! only places a word too long for a line may be cut.
std::vector<std::size_t> grapheme_ends(std::string_view utf8);

}  // namespace mallet::render
