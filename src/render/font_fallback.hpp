#pragma once
// The fonts a language's text is set in, found by fontconfig: the family named for the
// language (an operator's choice, else the Noto family of its script) first, then
// fontconfig's own order for "sans-serif" in that language, so that a letter the first font
// lacks comes from the next that has it. Each font is opened with FreeType at one pixel size
// and given to HarfBuzz for shaping.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// FreeType and HarfBuzz types, opaque here.
struct FT_FaceRec_;
struct hb_font_t;

namespace mallet::render {

//! Which family a language's text starts with. A language absent here starts with
//! default_family(); every language then falls back to fontconfig's order.
struct FontChoice {
  std::map<std::string, std::string, std::less<>> families;  //!< language → family ("Noto Sans Ethiopic")
};

//! The family a language is set in unless an operator names another: the Noto family of its
//! script (Debian's fonts-noto-core and fonts-noto-cjk).
std::string default_family(std::string_view language);

//! fontconfig's name for a language ("zh" → "zh-cn": Simplified Chinese glyph forms).
std::string fontconfig_language(std::string_view language);

//! One font file opened at a pixel size: its FreeType face and HarfBuzz font.
class Face {
 public:
  //! Throws FileError naming `file` if FreeType cannot open it.
  Face(const std::filesystem::path& file, int index, float pixel_height);
  ~Face();
  Face(const Face&) = delete;
  Face& operator=(const Face&) = delete;

  const std::filesystem::path& file() const { return file_; }
  int index() const { return index_; }  //!< the face's index in a collection (.ttc)
  std::string family() const;
  bool has(char32_t code_point) const;  //!< the font maps it to a glyph
  std::uint32_t glyph_index(char32_t code_point) const;  //!< its glyph as the font's cmap maps it (0: none)
  FT_FaceRec_* ft() const { return ft_; }
  hb_font_t* hb() const { return hb_; }

 private:
  std::filesystem::path file_;
  int index_ = 0;
  FT_FaceRec_* ft_ = nullptr;
  hb_font_t* hb_ = nullptr;
};

//! The fonts opened so far at one pixel size, each once whichever languages use it (their
//! glyphs are then cached once too).
class FaceLibrary {
 public:
  explicit FaceLibrary(float pixel_height) : pixel_height_(pixel_height) {}
  std::shared_ptr<const Face> open(const std::filesystem::path& file, int index);
  float pixel_height() const { return pixel_height_; }

 private:
  float pixel_height_;
  std::map<std::pair<std::string, int>, std::shared_ptr<const Face>> faces_;
};

//! The fonts of one language in the order they are tried. At least one: a language with no
//! font at all throws FileError naming fontconfig.
class FontFallback {
 public:
  FontFallback(std::string_view language, const FontChoice& choice, FaceLibrary& library);

  const std::string& language() const { return language_; }
  const std::vector<std::shared_ptr<const Face>>& faces() const { return faces_; }
  //! The first font that has `code_point`, or -1.
  int face_for(char32_t code_point) const;

 private:
  std::string language_;
  std::vector<std::shared_ptr<const Face>> faces_;
};

}  // namespace mallet::render
