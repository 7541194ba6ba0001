#include "render/font_atlas.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

// Declarations only: Debian's libstb.so carries stb_truetype's implementation.
#include <stb_truetype.h>

#include "core/file_error.hpp"

namespace mallet::render {
namespace {

constexpr char32_t kFirst = 0x20;   // the baked range, U+0020..U+00FF
constexpr char32_t kLast = 0xFF;
constexpr std::size_t kCount = kLast - kFirst + 1;
constexpr char32_t kFallback = U'?';

// Shapes sample a fully-covered block in the atlas's top-left corner. 3×3 so that the centre
// texel's bilinear neighbours are covered too (a uv a hair off the centre still reads 255);
// one empty row below it keeps it apart from the glyphs packed underneath.
constexpr int kSolidSize = 3;
constexpr int kReservedRows = kSolidSize + 1;

// Oversampling 2×1: glyphs placed at fractional x (centred text, kerning) stay sharp
// horizontally; vertically the caller puts the baseline on a whole pixel.
constexpr unsigned kOversampleX = 2;
constexpr unsigned kOversampleY = 1;
constexpr int kPadding = 1;
constexpr int kMaxAtlasSide = 8192;
constexpr float kMaxPixelHeight = 256.0f;

std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) |
         std::uint32_t{b[at + 3]};
}

// stb_truetype trusts the file it is given and reads out of bounds on garbage, so check the
// table directory first: every table it may look at must lie inside the file.
bool tables_inside(const std::vector<std::uint8_t>& ttf, std::size_t offset) {
  if (offset + 12 > ttf.size()) return false;
  const std::size_t tables = (std::size_t{ttf[offset + 4]} << 8) | ttf[offset + 5];
  if (tables == 0 || offset + 12 + tables * 16 > ttf.size()) return false;
  for (std::size_t i = 0; i < tables; ++i) {
    const std::size_t entry = offset + 12 + i * 16;
    const std::uint64_t start = be32(ttf, entry + 8), length = be32(ttf, entry + 12);
    if (start + length > ttf.size()) return false;
  }
  return true;
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

struct FontAtlas::Face {
  std::vector<std::uint8_t> ttf;
  stbtt_fontinfo info{};  // points into ttf: Face is never copied or moved once built
  //! What each baked code point draws as: itself, or '?' where the font has no glyph.
  std::array<char32_t, kCount> drawn{};

  Face() = default;
  Face(const Face&) = delete;
  Face& operator=(const Face&) = delete;

  char32_t draws_as(char32_t cp) const {
    return cp >= kFirst && cp <= kLast ? drawn[cp - kFirst] : kFallback;
  }
};

namespace {

//! The font file read and checked: every table inside it, stb_truetype's parse accepted.
std::shared_ptr<FontAtlas::Face> load_face(const std::filesystem::path& ttf, const char* package) {
  const std::string name = ttf.string();
  std::error_code ec;
  const auto status = std::filesystem::status(ttf, ec);
  if (!std::filesystem::exists(status))
    throw FileError(name, 0, 0, std::string("no such font file (Debian: apt install ") + package + ")");
  if (std::filesystem::is_directory(status)) throw FileError(name, 0, 0, "is a directory, not a font file");

  auto face = std::make_shared<FontAtlas::Face>();
  {
    std::ifstream in(ttf, std::ios::binary);
    if (!in) throw FileError(name, 0, 0, "cannot open the font file");
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0);
    if (size < 0) throw FileError(name, 0, 0, "cannot read the font file");
    face->ttf.resize(static_cast<std::size_t>(size));
    if (!in.read(reinterpret_cast<char*>(face->ttf.data()), size)) throw FileError(name, 0, 0, "read failed");
  }
  if (face->ttf.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw FileError(name, 0, 0, "font file too large");
  // GetFontOffsetForIndex reads a collection's header unchecked: 16 bytes at least.
  const int offset = face->ttf.size() < 16 ? -1 : stbtt_GetFontOffsetForIndex(face->ttf.data(), 0);
  if (offset < 0 || !tables_inside(face->ttf, static_cast<std::size_t>(offset)) ||
      stbtt_InitFont(&face->info, face->ttf.data(), offset) == 0)
    throw FileError(name, 0, 0, "not a usable TrueType font");
  return face;
}

//! The atlas area (texels) stb's packer will ask for a glyph, oversampling and padding included.
std::uint64_t packed_area(const stbtt_fontinfo* info, float scale, int glyph) {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  stbtt_GetGlyphBitmapBoxSubpixel(info, glyph, scale * kOversampleX, scale * kOversampleY, 0, 0, &x0, &y0, &x1, &y1);
  return static_cast<std::uint64_t>(x1 - x0 + kPadding + int{kOversampleX} - 1) *
         static_cast<std::uint64_t>(y1 - y0 + kPadding + int{kOversampleY} - 1);
}

}  // namespace

std::filesystem::path FontAtlas::default_font() { return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"; }

std::filesystem::path FontAtlas::default_cjk_font() {
  return "/usr/share/fonts/opentype/ipafont-gothic/ipag.ttf";
}

FontAtlas::FontAtlas(const std::filesystem::path& ttf, float pixel_height) : FontAtlas(ttf, pixel_height, {}, {}) {}

FontAtlas::FontAtlas(const std::filesystem::path& ttf, float pixel_height, std::string_view also,
                     const std::filesystem::path& also_font)
    : pixel_height_(pixel_height) {
  if (!(pixel_height > 0.0f && pixel_height <= kMaxPixelHeight))
    throw std::invalid_argument("FontAtlas: pixel_height must be in (0, 256], got " + std::to_string(pixel_height));
  const std::string name = ttf.string();
  std::shared_ptr<Face> face = load_face(ttf, "fonts-dejavu-core");
  stbtt_fontinfo* info = &face->info;

  scale_ = stbtt_ScaleForPixelHeight(info, pixel_height);
  int ascent = 0, descent = 0, line_gap = 0;
  stbtt_GetFontVMetrics(info, &ascent, &descent, &line_gap);
  ascent_ = static_cast<float>(ascent) * scale_;
  descent_ = -static_cast<float>(descent) * scale_;
  line_gap_ = static_cast<float>(line_gap) * scale_;

  // Pack only the code points a font has (stb's packer reports a failure for a missing one,
  // which would read as "does not fit"); the others draw as '?'.
  std::vector<int> present;
  std::uint64_t min_area = 0;
  for (char32_t cp = kFirst; cp <= kLast; ++cp) {
    const int glyph = stbtt_FindGlyphIndex(info, static_cast<int>(cp));
    face->drawn[cp - kFirst] = glyph != 0 ? cp : kFallback;
    if (glyph == 0) continue;
    present.push_back(static_cast<int>(cp));
    min_area += packed_area(info, scale_, glyph);
  }
  if (face->draws_as(kFallback) != kFallback) throw FileError(name, 0, 0, "the font has no '?' glyph");

  // The code points beyond Latin-1 that `also` uses, each once, in order: the main font's
  // where it has them, the second font's for the rest.
  std::u32string beyond = decode_utf8(also);
  std::erase_if(beyond, [](char32_t cp) { return cp <= kLast || cp == U'\uFFFD'; });
  std::sort(beyond.begin(), beyond.end());
  beyond.erase(std::unique(beyond.begin(), beyond.end()), beyond.end());
  std::shared_ptr<Face> second;
  std::vector<int> from_second;
  for (const char32_t cp : beyond) {
    if (const int glyph = stbtt_FindGlyphIndex(info, static_cast<int>(cp)); glyph != 0) {
      present.push_back(static_cast<int>(cp));
      min_area += packed_area(info, scale_, glyph);
      continue;
    }
    if (also_font.empty()) continue;
    if (!second) second = load_face(also_font, "fonts-ipafont-gothic");
    if (const int glyph = stbtt_FindGlyphIndex(&second->info, static_cast<int>(cp)); glyph != 0) {
      from_second.push_back(static_cast<int>(cp));
      min_area += packed_area(&second->info, stbtt_ScaleForPixelHeight(&second->info, pixel_height), glyph);
    }
  }

  // Smallest power-of-two atlas, square or twice as wide as high, that the packer fills:
  // 32×32, 64×32, 64×64, 128×64, ... Sizes with too little area for the glyphs are skipped
  // without packing.
  std::vector<stbtt_packedchar> packed(present.size()), packed_second(from_second.size());
  bool fits = false;
  for (int w = 32, h = 32; !fits;) {
    if (w > kMaxAtlasSide)
      throw std::runtime_error(name + ": glyphs at " + std::to_string(pixel_height) + " px do not fit a " +
                               std::to_string(kMaxAtlasSide) + " px atlas");
    const std::uint64_t usable = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h - kReservedRows);
    if (usable >= min_area) {
      coverage_.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
      // Glyphs go below the reserved rows: the packer sees a shorter image starting there.
      stbtt_pack_context pack{};
      if (stbtt_PackBegin(&pack, coverage_.data() + static_cast<std::size_t>(kReservedRows) * w, w,
                          h - kReservedRows, w, kPadding, nullptr) == 0)
        throw std::bad_alloc();
      stbtt_PackSetOversampling(&pack, kOversampleX, kOversampleY);
      auto pack_from = [&](const Face& f, std::vector<int>& code_points, std::vector<stbtt_packedchar>& out) {
        if (code_points.empty()) return true;
        stbtt_pack_range range{};
        range.font_size = pixel_height;
        range.array_of_unicode_codepoints = code_points.data();
        range.num_chars = static_cast<int>(code_points.size());
        range.chardata_for_range = out.data();
        // stb takes the font's index in a collection, not its byte offset: the first, as
        // load_face parsed (a collection's first font lies past its header, at offset > 0).
        return stbtt_PackFontRanges(&pack, f.ttf.data(), 0, &range, 1) != 0;
      };
      fits = pack_from(*face, present, packed) && (!second || pack_from(*second, from_second, packed_second));
      stbtt_PackEnd(&pack);
      if (fits) {
        width_ = w;
        height_ = h;
      }
    }
    if (w == h)
      w *= 2;
    else
      h *= 2;
  }

  for (int y = 0; y < kSolidSize; ++y)
    for (int x = 0; x < kSolidSize; ++x) coverage_[static_cast<std::size_t>(y) * width_ + x] = 255;
  const float centre = static_cast<float>(kSolidSize / 2) + 0.5f;  // the centre texel's centre
  solid_u_ = centre / static_cast<float>(width_);
  solid_v_ = centre / static_cast<float>(height_);

  glyphs_.assign(kCount, GlyphQuad{});
  const float iw = 1.0f / static_cast<float>(width_), ih = 1.0f / static_cast<float>(height_);
  auto quad = [&](const stbtt_packedchar& p) {
    GlyphQuad q;
    q.x0 = p.xoff;
    q.y0 = p.yoff;
    q.x1 = p.xoff2;
    q.y1 = p.yoff2;
    q.u0 = static_cast<float>(p.x0) * iw;
    q.u1 = static_cast<float>(p.x1) * iw;
    q.v0 = static_cast<float>(p.y0 + kReservedRows) * ih;
    q.v1 = static_cast<float>(p.y1 + kReservedRows) * ih;
    q.advance = p.xadvance;
    return q;
  };
  for (std::size_t i = 0; i < present.size(); ++i) {
    const auto cp = static_cast<char32_t>(present[i]);
    if (cp <= kLast) glyphs_[cp - kFirst] = quad(packed[i]);
    else beyond_.emplace_back(cp, quad(packed[i]));
  }
  for (std::size_t i = 0; i < from_second.size(); ++i)
    beyond_.emplace_back(static_cast<char32_t>(from_second[i]), quad(packed_second[i]));
  std::sort(beyond_.begin(), beyond_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (char32_t cp = kFirst; cp <= kLast; ++cp)
    if (face->drawn[cp - kFirst] != cp) glyphs_[cp - kFirst] = glyphs_[kFallback - kFirst];
  face_ = std::move(face);
}

const GlyphQuad* FontAtlas::beyond(char32_t code_point) const {
  const auto it = std::lower_bound(beyond_.begin(), beyond_.end(), code_point,
                                   [](const auto& entry, char32_t cp) { return entry.first < cp; });
  return it != beyond_.end() && it->first == code_point ? &it->second : nullptr;
}

bool FontAtlas::has(char32_t code_point) const {
  if (code_point <= kLast) return face_->draws_as(code_point) == code_point;
  return beyond(code_point) != nullptr;
}

GlyphQuad FontAtlas::glyph(char32_t code_point) const {
  if (code_point > kLast)
    if (const GlyphQuad* q = beyond(code_point)) return *q;
  return glyphs_[face_->draws_as(code_point) - kFirst];
}

float FontAtlas::kerning(char32_t left, char32_t right) const {
  if (left > kLast || right > kLast) return 0;  // beyond Latin-1 (CJK): set solid, no pairs
  const int k = stbtt_GetCodepointKernAdvance(&face_->info, static_cast<int>(face_->draws_as(left)),
                                              static_cast<int>(face_->draws_as(right)));
  return static_cast<float>(k) * scale_;
}

float FontAtlas::measure(std::string_view utf8) const {
  const std::u32string text = decode_utf8(utf8);
  float width = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    width += glyph(text[i]).advance;
    if (i + 1 < text.size()) width += kerning(text[i], text[i + 1]);
  }
  return width;
}

}  // namespace mallet::render
