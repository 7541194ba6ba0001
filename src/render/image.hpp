#pragma once
// An 8-bit RGBA image in memory (what the offscreen target reads back, what goldens are),
// PNG in and out, and the comparison the golden tests use.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace mallet::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  //!< tightly packed, rows top to bottom, width·height·4 bytes

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0) {}
  std::uint8_t* at(int x, int y) { return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  const std::uint8_t* at(int x, int y) const {
    return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
};

//! Writes an RGBA PNG atomically (temporary file, then rename). Throws std::runtime_error
//! naming the file on failure (the parent folder is not created), std::invalid_argument for
//! an image whose buffer does not match its size.
void write_png(const Image& image, const std::filesystem::path& file);

//! Reads a PNG as RGBA8. Throws FileError naming the file and the problem.
Image read_png(const std::filesystem::path& file);

struct ImageDiff {
  bool same_size = false;
  int max_channel_delta = 0;          //!< largest |a − e| over all pixels and channels
  std::uint64_t differing_pixels = 0; //!< pixels with some channel delta > tolerance
  double differing_fraction = 0.0;    //!< differing_pixels / pixel count
  double rms = 0.0;                   //!< root-mean-square channel delta, in 1/255 units
  //! Visualisation, opaque: the expected image in dim grey where the pixels agree, solid red
  //! (255,0,0,255) where they differ; with different sizes, the actual image's frame all red.
  Image difference;
};

//! Compares `actual` with `expected`; a pixel differs when a channel is off by more than
//! `tolerance` (0..255, else std::invalid_argument). Images of different sizes give
//! same_size = false and everything at its worst: differing_fraction 1, differing_pixels the
//! larger pixel count, max_channel_delta 255, rms 255.
ImageDiff compare_images(const Image& actual, const Image& expected, int tolerance);

//! Box-filters an image down by an integer factor (the supersampled reference of the
//! antialiasing benchmark). Width and height must be multiples of `factor` (else
//! std::invalid_argument). Each channel, alpha too, is the mean of its box in the stored 8-bit
//! values, rounded to nearest.
Image downsample(const Image& image, int factor);

}  // namespace mallet::render
