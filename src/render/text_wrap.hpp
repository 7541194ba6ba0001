#pragma once
// Lines of a text that fit a width, as a font sets them: broken at spaces (which are dropped)
// and, in Japanese, between characters, but never before closing punctuation (、。）」…) nor
// after opening punctuation (（「…), the simple rule of Japanese line breaking (kinsoku).
#include <string>
#include <string_view>
#include <vector>

#include "render/font_atlas.hpp"

namespace mallet::render {

//! Greedy: each line takes as much as fits `max_width` pixels. A word (or an unbreakable run)
//! wider than that is cut between characters. An empty text gives no lines.
std::vector<std::string> wrap_text(const FontAtlas& font, std::string_view utf8, float max_width);

}  // namespace mallet::render
