#include "render/font_atlas.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <ft2build.h>
#include FT_FREETYPE_H

#include "core/visitor_language.hpp"

namespace mallet::render {
namespace {

// Shapes sample a fully-covered block in the atlas's top-left corner. 3×3 so that the centre
// texel's bilinear neighbours are covered too (a uv a hair off the centre still reads 255);
// one empty row below it keeps it apart from the glyphs packed underneath.
constexpr int kSolidSize = 3;
constexpr int kReservedRows = kSolidSize + 1;
constexpr int kPadding = 1;  // empty texels around each glyph: the linear filter reads no neighbour
constexpr int kMaxAtlasSide = 8192;
constexpr float kMaxPixelHeight = 256.0f;
//! Texts kept set: more (a screen's changing numbers over weeks) and the cache starts again.
constexpr std::size_t kMaxTexts = 4096;

//! The atlas's side: room for at least 24 × 24 glyph boxes of a line's height, about two
//! thousand glyphs (a Latin letter takes half a box), where one language's screen draws 50 to
//! 250 (`mallet bench render`): the nine shipped languages' screens fit at once, nearly.
//! 2048 × 2048 at 1080p (4 MiB).
int atlas_side(float pixel_height) {
  const int box = static_cast<int>(std::ceil(pixel_height * 1.4f)) + 2 * kPadding;
  int side = 256;
  while (side < 24 * box && side < kMaxAtlasSide) side *= 2;
  return side;
}

}  // namespace

std::u32string decode_utf8(std::string_view utf8) {
  std::u32string out;
  out.reserve(utf8.size());
  std::size_t i = 0;
  while (i < utf8.size()) {
    const auto lead = static_cast<unsigned char>(utf8[i]);
    if (lead < 0x80) {
      out.push_back(lead);
      ++i;
      continue;
    }
    // Well-formed sequences per the Unicode standard's table 3-7: the second byte's range
    // depends on the lead so that overlong forms, surrogates and > U+10FFFF are rejected.
    std::size_t length = 0;
    char32_t cp = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
      cp = lead & 0x1Fu;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      cp = lead & 0x0Fu;
      if (lead == 0xE0) lo = 0xA0;
      if (lead == 0xED) hi = 0x9F;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      cp = lead & 0x07u;
      if (lead == 0xF0) lo = 0x90;
      if (lead == 0xF4) hi = 0x8F;
    } else {
      out.push_back(U'\uFFFD');
      ++i;
      continue;
    }
    std::size_t taken = 1;
    for (; taken < length && i + taken < utf8.size(); ++taken) {
      const auto b = static_cast<unsigned char>(utf8[i + taken]);
      if (b < (taken == 1 ? lo : 0x80) || b > (taken == 1 ? hi : 0xBF)) break;
      cp = static_cast<char32_t>((cp << 6) | (b & 0x3Fu));
    }
    // A broken sequence becomes one U+FFFD for its longest valid start (the "maximal
    // subpart" practice), and the byte that broke it starts the next sequence.
    out.push_back(taken == length ? cp : U'\uFFFD');
    i += taken;
  }
  return out;
}

FontAtlas::FontAtlas(float pixel_height, FontChoice choice)
    : pixel_height_(pixel_height), choice_(std::move(choice)) {
  if (!(pixel_height > 0.0f && pixel_height <= kMaxPixelHeight))
    throw std::invalid_argument("FontAtlas: pixel_height must be in (0, 256], got " + std::to_string(pixel_height));
  library_ = std::make_unique<FaceLibrary>(pixel_height);
  // The line's metrics are Latin's font's (the sizes every layout was made with): the same in
  // every language, so that a banner keeps its place when the language changes.
  const FT_Size_Metrics& m = fonts("en").faces().front()->ft()->size->metrics;
  ascent_ = static_cast<float>(m.ascender) / 64.0f;
  descent_ = -static_cast<float>(m.descender) / 64.0f;
  line_gap_ = std::max(0.0f, static_cast<float>(m.height) / 64.0f - ascent_ - descent_);
  width_ = height_ = atlas_side(pixel_height);
  coverage_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
  const float centre = static_cast<float>(kSolidSize / 2) + 0.5f;  // the centre texel's centre
  solid_u_ = centre / static_cast<float>(width_);
  solid_v_ = centre / static_cast<float>(height_);
  start_empty();
}

FontAtlas::~FontAtlas() {
  // The shaped texts point at faces the library owns, the fallbacks share them: drop those first.
  shaped_.clear();
  fallbacks_.clear();
}

void FontAtlas::start_empty() const {
  std::fill(coverage_.begin(), coverage_.end(), std::uint8_t{0});
  for (int y = 0; y < kSolidSize; ++y)
    for (int x = 0; x < kSolidSize; ++x) coverage_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x] = 255;
  slots_.clear();
  shelf_x_ = 0;
  shelf_y_ = kReservedRows;
  shelf_height_ = 0;
  ++generation_;
}

const FontFallback& FontAtlas::fonts(std::string_view language) const {
  auto it = fallbacks_.find(std::string(language));
  if (it == fallbacks_.end())
    it = fallbacks_.emplace(std::string(language), std::make_unique<FontFallback>(language, choice_, *library_)).first;
  return *it->second;
}

const ShapedText& FontAtlas::shape_in(std::string_view language, std::string_view utf8) const {
  std::string key;
  key.reserve(language.size() + 1 + utf8.size());
  key.append(language).push_back('\x1f');
  key.append(utf8);
  if (const auto it = shaped_.find(key); it != shaped_.end()) return it->second;
  if (shaped_.size() >= kMaxTexts) shaped_.clear();
  ++shapings_;
  return shaped_.emplace(std::move(key), shape_text(fonts(language), utf8)).first->second;
}

const ShapedText& FontAtlas::shape(std::string_view utf8) const { return shape_in(visitor_language(), utf8); }

void FontAtlas::warm(std::string_view language, const std::vector<std::string>& texts) const {
  for (const std::string& text : texts)
    for (const PlacedGlyph& g : shape_in(language, text).glyphs) quad(g);
}

bool FontAtlas::has_in(std::string_view language, char32_t code_point) const {
  return fonts(language).face_for(code_point) >= 0;
}

bool FontAtlas::has(char32_t code_point) const { return has_in(visitor_language(), code_point); }

std::vector<std::string> FontAtlas::missing_letters(std::string_view language, std::string_view utf8,
                                                    std::size_t most) const {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < utf8.size() && out.size() < most;) {
    std::size_t length = 1;  // the letter's bytes: its lead byte and the continuation bytes after it
    while (i + length < utf8.size() && (static_cast<unsigned char>(utf8[i + length]) & 0xC0) == 0x80) ++length;
    const std::string_view letter = utf8.substr(i, length);
    i += length;
    const std::u32string code = decode_utf8(letter);
    if (code.size() != 1) continue;
    const char32_t c = code[0];
    if (c < 0x21 || c == 0x7F || c == 0x3000 || c == 0x200C || c == 0x200D || c == 0xFFFD) continue;
    if (!has_in(language, c) && std::find(out.begin(), out.end(), letter) == out.end()) out.emplace_back(letter);
  }
  return out;
}

std::optional<FontAtlas::Slot> FontAtlas::draw_glyph(const PlacedGlyph& glyph) const {
  FT_Face ft = glyph.face->ft();
  // Unhinted, as HarfBuzz placed it (font_fallback.cpp), antialiased.
  if (FT_Load_Glyph(ft, glyph.glyph, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP | FT_LOAD_RENDER) != 0)
    return Slot{};  // a glyph FreeType cannot draw: nothing, rather than the kiosk's end
  const FT_Bitmap& bitmap = ft->glyph->bitmap;
  const int w = static_cast<int>(bitmap.width), h = static_cast<int>(bitmap.rows);
  if (w == 0 || h == 0 || bitmap.pixel_mode != FT_PIXEL_MODE_GRAY) return Slot{};
  if (w + 2 * kPadding > width_ || h + 2 * kPadding > height_ - kReservedRows) return Slot{};  // larger than the atlas
  if (shelf_x_ + w + 2 * kPadding > width_) {  // the next row
    shelf_y_ += shelf_height_;
    shelf_x_ = 0;
    shelf_height_ = 0;
  }
  if (shelf_y_ + h + 2 * kPadding > height_) return std::nullopt;  // full
  const int x = shelf_x_ + kPadding, y = shelf_y_ + kPadding;
  for (int row = 0; row < h; ++row)
    std::copy_n(bitmap.buffer + static_cast<std::ptrdiff_t>(row) * bitmap.pitch, w,
                coverage_.begin() + static_cast<std::ptrdiff_t>(y + row) * width_ + x);
  shelf_x_ += w + 2 * kPadding;
  shelf_height_ = std::max(shelf_height_, h + 2 * kPadding);
  ++generation_;
  Slot slot;
  slot.ink = true;
  const float left = static_cast<float>(ft->glyph->bitmap_left), top = static_cast<float>(ft->glyph->bitmap_top);
  slot.quad = {left, -top, left + static_cast<float>(w), -top + static_cast<float>(h),
               static_cast<float>(x) / static_cast<float>(width_), static_cast<float>(y) / static_cast<float>(height_),
               static_cast<float>(x + w) / static_cast<float>(width_), static_cast<float>(y + h) / static_cast<float>(height_)};
  return slot;
}

std::optional<GlyphQuad> FontAtlas::quad(const PlacedGlyph& glyph) const {
  if (!glyph.face) return std::nullopt;
  const GlyphKey key{glyph.face, glyph.glyph};
  auto it = slots_.find(key);
  if (it == slots_.end()) {
    std::optional<Slot> drawn = draw_glyph(glyph);
    if (!drawn) {  // full: start again; what this frame drew before shows right from the next
      start_empty();
      drawn = draw_glyph(glyph);
      if (!drawn) drawn = Slot{};
    }
    it = slots_.emplace(key, *drawn).first;
  }
  if (!it->second.ink) return std::nullopt;
  return it->second.quad;
}

}  // namespace mallet::render
