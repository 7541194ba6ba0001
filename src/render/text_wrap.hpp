#pragma once
// Lines of a text that fit a width, as its language breaks lines: Unicode line breaking
// (UAX #14, render/text_shaping.hpp), so that a line ends only where the language allows
// (after a space; between Japanese phrases, never inside a word such as 言語; between Thai
// words; never before closing punctuation nor after opening punctuation), and between words
// (a path or a Korean word is kept whole unless wider than a line). The spaces where a line
// ends are dropped.
#include <string>
#include <string_view>
#include <vector>

#include "render/font_atlas.hpp"

namespace mallet::render {

//! Greedy: each line takes as much as fits `max_width` pixels, set in the visitor's language.
//! A word wider than that is cut between characters (grapheme clusters). A newline ends a
//! line. An empty text gives no lines.
std::vector<std::string> wrap_text(const FontAtlas& font, std::string_view utf8, float max_width);
//! The same in `language`'s fonts and rules.
std::vector<std::string> wrap_text_in(const FontAtlas& font, std::string_view language, std::string_view utf8,
                                      float max_width);

}  // namespace mallet::render
