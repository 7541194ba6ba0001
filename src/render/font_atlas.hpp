#pragma once
// The overlay's letters: text in any language set by FreeType, HarfBuzz, fontconfig and ICU
// (render/font_fallback.hpp, render/text_shaping.hpp), and its glyphs drawn on demand into
// one single-channel coverage atlas that the overlay samples. No text needs to be known
// before it is shown: a string is set the first time it is drawn and kept (never set twice
// while unchanged), a glyph drawn into the atlas the first time it is needed.
//
// Text is set in the visitor's language (core/visitor_language.hpp) at the time it is drawn:
// its fonts, its direction, its line breaking.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "render/font_fallback.hpp"
#include "render/text_shaping.hpp"

namespace mallet::render {

struct GlyphQuad {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  //!< pixels relative to the glyph's origin on the baseline, y down
  float u0 = 0, v0 = 0, u1 = 0, v1 = 0;  //!< atlas coordinates
};

//! Decodes UTF-8; every malformed sequence (stray or missing continuation bytes, overlong
//! forms, surrogates, beyond U+10FFFF) becomes one U+FFFD and decoding goes on after it.
std::u32string decode_utf8(std::string_view utf8);

//! A cache: its const functions set text and draw glyphs as they are asked for. One thread
//! (the one that draws) uses it.
class FontAtlas {
 public:
  //! Letters `pixel_height` tall from capital to descender, in the fonts `choice` names or
  //! else Noto's. Throws std::invalid_argument for a pixel_height outside (0, 256], FileError
  //! if fontconfig finds no font at all.
  explicit FontAtlas(float pixel_height, FontChoice choice = {});
  ~FontAtlas();
  FontAtlas(const FontAtlas&) = delete;
  FontAtlas& operator=(const FontAtlas&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& coverage() const { return coverage_; }  //!< width·height bytes
  //! Counts every change to coverage(): the GPU's copy is up to date while it is unchanged.
  std::uint64_t generation() const { return generation_; }
  float pixel_height() const { return pixel_height_; }
  float ascent() const { return ascent_; }    //!< pixels above the baseline (Latin's font)
  float descent() const { return descent_; }  //!< pixels below the baseline (positive)
  float line_gap() const { return line_gap_; }
  //! Atlas coordinates of a fully-covered texel (shapes sample it).
  float solid_u() const { return solid_u_; }
  float solid_v() const { return solid_v_; }

  //! `utf8` set in the visitor's language (the one in use now), kept for the next time. The
  //! reference holds until the next text is set (the cache may start again then).
  const ShapedText& shape(std::string_view utf8) const;
  const ShapedText& shape_in(std::string_view language, std::string_view utf8) const;
  //! Width in pixels of `utf8` set in the visitor's language.
  float measure(std::string_view utf8) const { return shape(utf8).width; }
  //! A glyph's quad, drawn into the atlas if it is not yet; nullopt for one with no ink (a
  //! space). An atlas too full for it starts again empty (generation() tells the GPU).
  std::optional<GlyphQuad> quad(const PlacedGlyph& glyph) const;

  //! Sets each of `texts` in `language` and draws their glyphs now: what a screen will show,
  //! ready before its first frame (the kiosk's start warms its language's catalogue), so that
  //! showing it costs no shaping and no copy of the atlas to the GPU then.
  void warm(std::string_view language, const std::vector<std::string>& texts) const;

  //! Whether a font of `language` has `code_point` (false: it draws as the font's box).
  bool has_in(std::string_view language, char32_t code_point) const;
  bool has(char32_t code_point) const;  //!< in the visitor's language
  //! Up to `most` of the letters of `utf8` (as written, each once) that no font of `language`
  //! has; spaces, joiners and controls are not letters.
  std::vector<std::string> missing_letters(std::string_view language, std::string_view utf8, std::size_t most) const;
  //! `language`'s fonts, found the first time they are needed.
  const FontFallback& fonts(std::string_view language) const;

  //! Texts set and kept, glyphs looked at (in the atlas, or known to have no ink: a space):
  //! what the cache holds (the benchmark reports it).
  std::size_t texts_set() const { return shaped_.size(); }
  std::size_t glyphs_drawn() const { return slots_.size(); }
  std::uint64_t shapings() const { return shapings_; }  //!< times any text was set, ever

 private:
  struct Slot {
    bool ink = false;
    GlyphQuad quad;
  };
  struct GlyphKey {
    const Face* face;
    std::uint32_t glyph;
    bool operator==(const GlyphKey&) const = default;
  };
  struct GlyphKeyHash {
    std::size_t operator()(const GlyphKey& k) const {
      return std::hash<const void*>()(k.face) ^ (std::hash<std::uint32_t>()(k.glyph) * 0x9E3779B97F4A7C15ull);
    }
  };
  void start_empty() const;  //!< the atlas cleared but for its solid block
  std::optional<Slot> draw_glyph(const PlacedGlyph& glyph) const;

  float pixel_height_ = 0, ascent_ = 0, descent_ = 0, line_gap_ = 0;
  float solid_u_ = 0, solid_v_ = 0;
  int width_ = 0, height_ = 0;
  FontChoice choice_;
  std::unique_ptr<FaceLibrary> library_;
  mutable std::vector<std::uint8_t> coverage_;
  mutable std::uint64_t generation_ = 0;
  mutable std::uint64_t shapings_ = 0;
  mutable std::unordered_map<std::string, std::unique_ptr<FontFallback>> fallbacks_;
  mutable std::unordered_map<std::string, ShapedText> shaped_;  //!< key: language, '\x1f', text
  mutable std::unordered_map<GlyphKey, Slot, GlyphKeyHash> slots_;
  mutable int shelf_x_ = 0, shelf_y_ = 0, shelf_height_ = 0;  //!< the packer's open row
};

}  // namespace mallet::render
