#include "render/font_fallback.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <hb-ft.h>
#include <hb.h>

#include "core/file_error.hpp"

namespace mallet::render {
namespace {

//! How many fonts a language tries in all: its own, then fontconfig's next best. Enough for
//! every script a catalogue mixes (a Latin key name in a Japanese line); few enough that a
//! missing letter is found missing quickly.
constexpr std::size_t kMaxFaces = 8;

//! The em at a pixel height: letters as tall as the kiosk's text was when its pixel height
//! spanned DejaVu Sans's ascent to descent (every layout's sizes were chosen then), so that
//! Noto Sans's capitals stand 0.62 of the pixel height.
constexpr float kEmPerPixelHeight = 0.875f;

FT_Library freetype() {
  static FT_Library library = [] {
    FT_Library l = nullptr;
    if (FT_Init_FreeType(&l) != 0) throw std::runtime_error("FreeType: cannot initialise");
    return l;
  }();
  return library;
}

}  // namespace

std::string default_family(std::string_view language) {
  if (language == "ja") return "Noto Sans CJK JP";
  if (language == "zh") return "Noto Sans CJK SC";
  if (language == "ko") return "Noto Sans CJK KR";
  if (language == "ar" || language == "fa" || language == "ur") return "Noto Sans Arabic";
  if (language == "he" || language == "yi") return "Noto Sans Hebrew";
  if (language == "hi" || language == "mr" || language == "ne") return "Noto Sans Devanagari";
  if (language == "th") return "Noto Sans Thai";
  return "Noto Sans";
}

std::string fontconfig_language(std::string_view language) {
  if (language == "zh") return "zh-cn";
  return std::string(language);
}

Face::Face(const std::filesystem::path& file, int index, float pixel_height) : file_(file), index_(index) {
  if (FT_New_Face(freetype(), file.c_str(), index, &ft_) != 0)
    throw FileError(file.string(), 0, 0, "FreeType cannot open this font (face " + std::to_string(index) + ")");
  const auto em = static_cast<FT_F26Dot6>(std::lround(pixel_height * kEmPerPixelHeight * 64.0f));
  if (!FT_IS_SCALABLE(ft_) || FT_Set_Char_Size(ft_, 0, em, 72, 72) != 0) {
    FT_Done_Face(ft_);
    throw FileError(file.string(), 0, 0, "not a scalable font");
  }
  hb_ = hb_ft_font_create_referenced(ft_);
  // Unhinted outlines, as the glyphs are drawn (glyph_cache): HarfBuzz's advances then match
  // the drawn widths exactly at every size.
  hb_ft_font_set_load_flags(hb_, FT_LOAD_NO_HINTING);
}

Face::~Face() {
  hb_font_destroy(hb_);  // releases its reference to the face
  FT_Done_Face(ft_);
}

std::string Face::family() const { return ft_->family_name ? ft_->family_name : file_.filename().string(); }

bool Face::has(char32_t code_point) const { return glyph_index(code_point) != 0; }

std::uint32_t Face::glyph_index(char32_t code_point) const { return FT_Get_Char_Index(ft_, code_point); }

std::shared_ptr<const Face> FaceLibrary::open(const std::filesystem::path& file, int index) {
  auto& slot = faces_[{file.string(), index}];
  if (!slot) slot = std::make_shared<const Face>(file, index, pixel_height_);
  return slot;
}

FontFallback::FontFallback(std::string_view language, const FontChoice& choice, FaceLibrary& library)
    : language_(language) {
  static std::mutex fc_mutex;  // fontconfig's default configuration is shared
  const std::lock_guard lock(fc_mutex);
  if (FcInit() == FcFalse) throw FileError("fontconfig", 0, 0, "cannot read its configuration (/etc/fonts)");
  const auto named = choice.families.find(language);
  const std::string family = named != choice.families.end() ? named->second : default_family(language);
  FcPattern* pattern = FcPatternCreate();
  FcPatternAddString(pattern, FC_FAMILY, reinterpret_cast<const FcChar8*>(family.c_str()));
  FcPatternAddString(pattern, FC_FAMILY, reinterpret_cast<const FcChar8*>("sans-serif"));
  const std::string fc_lang = fontconfig_language(language);
  FcPatternAddString(pattern, FC_LANG, reinterpret_cast<const FcChar8*>(fc_lang.c_str()));
  FcPatternAddBool(pattern, FC_SCALABLE, FcTrue);
  FcConfigSubstitute(nullptr, pattern, FcMatchPattern);
  FcDefaultSubstitute(pattern);
  FcResult result = FcResultNoMatch;
  FcFontSet* set = FcFontSort(nullptr, pattern, FcTrue, nullptr, &result);
  std::string problem;
  for (int i = 0; set && i < set->nfont && faces_.size() < kMaxFaces; ++i) {
    FcChar8* file = nullptr;
    int index = 0;
    FcBool scalable = FcFalse;
    if (FcPatternGetString(set->fonts[i], FC_FILE, 0, &file) != FcResultMatch) continue;
    FcPatternGetInteger(set->fonts[i], FC_INDEX, 0, &index);
    if (FcPatternGetBool(set->fonts[i], FC_SCALABLE, 0, &scalable) == FcResultMatch && !scalable) continue;
    try {
      std::shared_ptr<const Face> face = library.open(reinterpret_cast<const char*>(file), index);
      if (std::none_of(faces_.begin(), faces_.end(), [&](const auto& f) { return f == face; }))
        faces_.push_back(std::move(face));
    } catch (const FileError& e) {
      if (problem.empty()) problem = e.what();
    }
  }
  if (set) FcFontSetDestroy(set);
  FcPatternDestroy(pattern);
  if (faces_.empty())
    throw FileError("fontconfig", 0, 0,
                    "no font for language '" + std::string(language) + "'" + (problem.empty() ? "" : ": " + problem) +
                        " (Debian: apt install fonts-noto-core fonts-noto-cjk)");
}

int FontFallback::face_for(char32_t code_point) const {
  for (std::size_t i = 0; i < faces_.size(); ++i)
    if (faces_[i]->has(code_point)) return static_cast<int>(i);
  return -1;
}

}  // namespace mallet::render
