#include "render/text_wrap.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

namespace mallet::render {
namespace {

//! Bytes in the UTF-8 sequence that starts with `lead` (1 for a byte that cannot lead one:
//! the font draws broken text as '?', and the cut falls between bytes no worse).
std::size_t sequence_length(unsigned char lead) {
  if (lead >= 0xF0 && lead <= 0xF4) return 4;
  if (lead >= 0xE0) return lead <= 0xEF ? 3 : 1;
  if (lead >= 0xC2) return 2;
  return 1;
}

bool ideographic(char32_t cp) {  // CJK punctuation, kana, ideographs, full-width forms
  return (cp >= 0x3000 && cp <= 0x9FFF) || (cp >= 0xF900 && cp <= 0xFAFF) || (cp >= 0xFF00 && cp <= 0xFFEF);
}

bool closing(char32_t cp) {  // may not begin a line
  for (const char32_t c : std::u32string_view(U"、。，．）」』】！？：；ー…・ぁぃぅぇぉっゃゅょァィゥェォッャュョ"))
    if (c == cp) return true;
  return false;
}

bool opening(char32_t cp) {  // may not end a line
  for (const char32_t c : std::u32string_view(U"（「『【"))
    if (c == cp) return true;
  return false;
}

struct CodePoint {
  std::size_t at, length;
  char32_t value;
};

}  // namespace

std::vector<std::string> wrap_text(const FontAtlas& font, std::string_view utf8, float max_width) {
  std::vector<CodePoint> cps;
  for (std::size_t i = 0; i < utf8.size();) {
    const std::size_t n = std::min(sequence_length(static_cast<unsigned char>(utf8[i])), utf8.size() - i);
    const std::u32string decoded = decode_utf8(utf8.substr(i, n));
    cps.push_back({i, n, decoded.size() == 1 ? decoded[0] : U'\uFFFD'});
    i += n;
  }
  std::vector<std::string> lines;
  std::size_t start = 0;  // index into cps of the line's first code point
  while (start < cps.size()) {
    while (start < cps.size() && cps[start].value == U' ') ++start;  // a line never starts with a space
    if (start == cps.size()) break;
    std::optional<std::size_t> cut;  // where the line may end (exclusive), the last that fits
    // width[k - start]: [start, k) as FontAtlas::measure sets it (each advance, then the
    // kerning with the next, summed in that order), grown one code point at a time.
    std::vector<float> width{0.0f};
    for (std::size_t i = start + 1; i <= cps.size(); ++i) {
      float w = width.back();
      if (i - 1 > start) w += font.kerning(cps[i - 2].value, cps[i - 1].value);
      width.push_back(w + font.glyph(cps[i - 1].value).advance);
      const bool last = i == cps.size();
      const bool may_break =
          last || cps[i].value == U' ' ||
          ((ideographic(cps[i].value) || ideographic(cps[i - 1].value)) && !closing(cps[i].value) &&
           !opening(cps[i - 1].value));
      if (!may_break) continue;
      if (width.back() > max_width && cut) break;
      cut = i;
      if (width.back() > max_width) break;  // the first piece alone is too wide
    }
    std::size_t end = *cut;
    // A first piece wider than the line: cut it between characters where it stops fitting.
    if (width[end - start] > max_width) {
      std::size_t fit = start + 1;
      while (fit < end && width[fit + 1 - start] <= max_width) ++fit;
      end = fit;
    }
    const std::size_t from = cps[start].at;
    std::size_t last = end;
    while (last > start && cps[last - 1].value == U' ') --last;  // no trailing space
    lines.emplace_back(utf8.substr(from, cps[last - 1].at + cps[last - 1].length - from));
    start = end;
  }
  return lines;
}

}  // namespace mallet::render
