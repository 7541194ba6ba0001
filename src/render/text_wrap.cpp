#include "render/text_wrap.hpp"

#include <algorithm>
#include <cstddef>

#include "core/visitor_language.hpp"
#include "render/text_shaping.hpp"

namespace mallet::render {
namespace {

//! `text` without the spaces (and the newline) a line ends with.
std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

}  // namespace

std::vector<std::string> wrap_text(const FontAtlas& font, std::string_view utf8, float max_width) {
  return wrap_text_in(font, visitor_language(), utf8, max_width);
}

std::vector<std::string> wrap_text_in(const FontAtlas& font, std::string_view language, std::string_view utf8,
                                      float max_width) {
  // A text that fits is one line (most do): set once, no line breaking to find.
  if (utf8.find('\n') == std::string_view::npos) {
    const std::string_view whole = trimmed(utf8.substr(std::min(utf8.find_first_not_of(' '), utf8.size())));
    if (whole.empty()) return {};
    if (font.shape_in(language, whole).width <= max_width) return {std::string(whole)};
  }
  // Lines end between words; a break inside a word (a path's /) only cuts a word too wide.
  std::vector<LineBreak> breaks = line_breaks(utf8, language);
  std::erase_if(breaks, [](const LineBreak& b) { return b.in_word; });
  std::vector<std::string> lines;
  auto width_of = [&](std::size_t from, std::size_t to) {
    return font.shape_in(language, trimmed(utf8.substr(from, to - from))).width;
  };
  std::size_t start = 0;
  std::size_t next = 0;  // the first break after start
  while (start < utf8.size()) {
    while (start < utf8.size() && utf8[start] == ' ') ++start;  // a line never starts with a space
    while (next < breaks.size() && breaks[next].at <= start) ++next;
    if (next == breaks.size()) break;
    // The last break that still fits; a hard break ends the line whatever follows.
    std::size_t chosen = next;
    if (width_of(start, breaks[next].at) <= max_width) {
      while (!breaks[chosen].hard && chosen + 1 < breaks.size() && width_of(start, breaks[chosen + 1].at) <= max_width)
        ++chosen;
    }
    std::size_t end = breaks[chosen].at;
    if (width_of(start, end) > max_width) {
      // A first piece wider than the line (a Japanese phrase, a long word, a path): cut it where
      // UAX #14 allows inside it (between ideographs but never before 、, after a path's /),
      // else between characters, as far as fits (at least one character a line, so that the
      // text always ends).
      const std::string_view piece = utf8.substr(start, end - start);
      std::size_t fit = 0;
      for (const LineBreak& b : line_breaks(piece, language, false)) {
        if (width_of(start, start + b.at) > max_width) break;
        fit = b.at;
      }
      if (fit == 0) {
        for (const std::size_t g : grapheme_ends(piece)) {
          if (fit != 0 && width_of(start, start + g) > max_width) break;
          fit = g;
        }
      }
      end = start + fit;
    }
    const std::string_view line = trimmed(utf8.substr(start, end - start));
    if (!line.empty() || (chosen < breaks.size() && breaks[chosen].hard)) lines.emplace_back(line);
    start = end;
  }
  return lines;
}

}  // namespace mallet::render
