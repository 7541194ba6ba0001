#include "wood_grain.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <stb_image_write.h>

namespace mallet::gen {

namespace {

// A 32-bit integer finaliser (good avalanche, fixed constants): the only source of
// randomness, so the texture is the same on every machine.
std::uint32_t mix(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

double hash01(std::int64_t i, std::int64_t j, std::uint32_t seed) {
  const std::uint32_t h =
      mix(static_cast<std::uint32_t>(i) * 0x9e3779b1U ^ mix(static_cast<std::uint32_t>(j) + seed * 0x85ebca77U));
  return static_cast<double>(h) / 4294967296.0;
}

double smoothstep(double t) { return t * t * (3.0 - 2.0 * t); }

// Value noise in [0, 1): hashed lattice values, smoothly interpolated.
double noise(double x, double y, std::uint32_t seed) {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx);
  const auto iy = static_cast<std::int64_t>(fy);
  const double tx = smoothstep(x - fx);
  const double ty = smoothstep(y - fy);
  const double top = std::lerp(hash01(ix, iy, seed), hash01(ix + 1, iy, seed), tx);
  const double bottom = std::lerp(hash01(ix, iy + 1, seed), hash01(ix + 1, iy + 1, seed), tx);
  return std::lerp(top, bottom, ty);
}

// Linear brightness of the grain at (u along the length, v across), both in [0, 1).
double grain(double u, double v, int height) {
  constexpr double kRings = 7.0;  // growth rings across the bar's width
  // Rings wander slowly along the length and are unevenly spaced across it.
  const double wander = 0.6 * (noise(u * 2.5, 0.0, 1) - 0.5) + 0.2 * (noise(u * 9.0, 0.0, 2) - 0.5);
  const double ring = v * kRings + wander + 0.8 * (noise(0.0, v * 6.0, 3) - 0.5);
  const double phase = ring - std::floor(ring);
  const double late_wood = std::exp(-std::pow((phase - 0.5) / 0.13, 2.0));  // the dark band of a ring
  // Pores: short streaks along the length, one texel tall.
  const double pore = noise(u * 24.0, v * static_cast<double>(height), 4);
  const double pores = pore > 0.8 ? (pore - 0.8) / 0.2 : 0.0;
  const double figure = noise(u * 6.0, v * 3.0, 5);  // broad, soft light and dark patches
  return std::clamp(0.95 - 0.35 * late_wood - 0.12 * pores - 0.12 * figure, 0.0, 1.0);
}

std::uint8_t srgb8(double linear) {
  const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
}

}  // namespace

RgbaImage wood_grain(int width, int height) {
  RgbaImage image{width, height, {}};
  image.rgba.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width;
      const double v = (y + 0.5) / height;
      const double g = grain(u, v, height) + 0.03 * (hash01(x, y, 6) - 0.5);  // texel noise
      const double shade = std::clamp(g, 0.0, 1.0);
      // Darker wood is a little warmer: blue and green fall faster than red.
      image.rgba.insert(image.rgba.end(),
                        {srgb8(shade), srgb8(std::pow(shade, 1.15)), srgb8(std::pow(shade, 1.3)), 255});
    }
  }
  return image;
}

std::vector<std::uint8_t> encode_png(const RgbaImage& image) {
  std::vector<std::uint8_t> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0) {
    throw std::runtime_error("cannot encode the wood grain as PNG");
  }
  return png;
}

}  // namespace mallet::gen
