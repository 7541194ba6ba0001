#pragma once
// Glyphs of one TrueType font (DejaVu Sans from Debian's fonts-dejavu-core by default)
// baked with stb_truetype into a single-channel coverage atlas at one pixel size; the glyphs
// of other scripts a text needs (Japanese) from a second font (IPAGothic, Debian's
// fonts-ipafont-gothic) in the same atlas.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mallet::render {

struct GlyphQuad {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  //!< pixels relative to the pen on the baseline, y down
  float u0 = 0, v0 = 0, u1 = 0, v1 = 0;  //!< atlas coordinates
  float advance = 0;                     //!< pen advance in pixels
};

//! Decodes UTF-8; every malformed sequence (stray or missing continuation bytes, overlong
//! forms, surrogates, beyond U+10FFFF) becomes one U+FFFD and decoding goes on after it.
std::u32string decode_utf8(std::string_view utf8);

//! Copyable and cheap to copy: copies share the (immutable) font file and its parsed tables.
class FontAtlas {
 public:
  //! Bakes code points U+0020..U+00FF (ASCII and Latin-1: the museum's languages) at
  //! `pixel_height`. Throws FileError naming the font file if it is missing or unusable,
  //! std::invalid_argument for a pixel_height outside (0, 256]. Code points the font lacks
  //! (DejaVu: the C1 controls U+007F..U+009F) draw as '?'.
  FontAtlas(const std::filesystem::path& ttf, float pixel_height);
  //! Also bakes every code point of `also` (UTF-8: the visitor languages' translations)
  //! beyond Latin-1: from `ttf` where it has the glyph, else from `also_font` (the same checks
  //! and errors as `ttf`; empty: none), else it draws as '?'.
  FontAtlas(const std::filesystem::path& ttf, float pixel_height, std::string_view also,
            const std::filesystem::path& also_font);

  static std::filesystem::path default_font();  //!< /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
  //! /usr/share/fonts/opentype/ipafont-gothic/ipag.ttf: kana and kanji (Japanese's glyph forms).
  static std::filesystem::path default_cjk_font();
  //! Whether `code_point` draws as itself (false: it draws as '?').
  bool has(char32_t code_point) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& coverage() const { return coverage_; }  //!< width·height bytes
  float pixel_height() const { return pixel_height_; }
  float ascent() const { return ascent_; }    //!< pixels above the baseline
  float descent() const { return descent_; }  //!< pixels below the baseline (positive)
  float line_gap() const { return line_gap_; }
  //! Atlas coordinates of a fully-covered texel (shapes sample it).
  float solid_u() const { return solid_u_; }
  float solid_v() const { return solid_v_; }
  //! The quad of a code point; code points outside the baked range draw as '?'.
  GlyphQuad glyph(char32_t code_point) const;
  //! Width in pixels of a UTF-8 string at this size (kerning included).
  float measure(std::string_view utf8) const;
  float kerning(char32_t left, char32_t right) const;  //!< pixels

  //! A font file and its stbtt_fontinfo (defined in font_atlas.cpp). stbtt_fontinfo points
  //! into the file's bytes, so the two live together behind one pointer that copies share.
  struct Face;

 private:
  int width_ = 0, height_ = 0;
  float pixel_height_ = 0, ascent_ = 0, descent_ = 0, line_gap_ = 0;
  float solid_u_ = 0, solid_v_ = 0;
  std::vector<std::uint8_t> coverage_;
  std::vector<GlyphQuad> glyphs_;   //!< U+0020..U+00FF
  std::vector<std::pair<char32_t, GlyphQuad>> beyond_;  //!< baked code points past U+00FF, sorted
  const GlyphQuad* beyond(char32_t code_point) const;  //!< its quad in beyond_, or null
  float scale_ = 0;                 //!< stb_truetype's scale for pixel_height
  std::shared_ptr<const Face> face_;  //!< the main font, kept for kerning
};

}  // namespace mallet::render
