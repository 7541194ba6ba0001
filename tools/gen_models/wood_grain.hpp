#pragma once
// The xylophone bars' procedural wood grain: a base-colour texture the material's
// rosewood factor tints. Deterministic: integer hashing with fixed seeds, no clock, no
// std::random distributions (whose output differs between standard libraries).
#include <cstdint>
#include <vector>

namespace mallet::gen {

struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  //!< rows top to bottom, sRGB-encoded as glTF colour textures are
};

//! Grain lines run along u (the image's width, the bar's length); they wander slowly
//! across v and carry fine pores. Light (≈0.4–0.95 linear) so the factor sets the hue.
RgbaImage wood_grain(int width, int height);

//! The image as PNG file bytes.
std::vector<std::uint8_t> encode_png(const RgbaImage& image);

}  // namespace mallet::gen
