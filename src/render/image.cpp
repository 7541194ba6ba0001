#include "render/image.hpp"


#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

// Declarations only: Debian's libstb.so carries the implementations.
#include <stb_image.h>
#include <stb_image_write.h>

#include "core/atomic_file.hpp"
#include "core/file_error.hpp"

namespace mallet::render {
namespace {

std::size_t pixel_count(const Image& image) {
  return static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
}

//! An Image whose buffer does not match its size is a caller's bug, not a file problem.
void check_image(const Image& image, const char* what) {
  if (image.width < 0 || image.height < 0 || image.rgba.size() != pixel_count(image) * 4)
    throw std::invalid_argument(std::string(what) + ": image of " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " holds " + std::to_string(image.rgba.size()) +
                                " bytes, not width*height*4");
}

std::string errno_text(int e) { return std::strerror(e); }

}  // namespace

void write_png(const Image& image, const std::filesystem::path& file) {
  check_image(image, "write_png");
  if (image.width == 0 || image.height == 0)
    throw std::runtime_error(file.string() + ": cannot write an empty image (PNG needs at least 1x1)");
  if (image.width > std::numeric_limits<int>::max() / 4)
    throw std::runtime_error(file.string() + ": image too wide for PNG encoding");

  // Encode in memory first so that I/O errors come from our own calls, with errno.
  std::vector<std::uint8_t> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0)
    throw std::runtime_error(file.string() + ": PNG encoding failed");

  // A reader (a golden test, an operator's viewer) never sees half a PNG.
  write_file_atomically(file, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

Image read_png(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) throw FileError(name, 0, 0, "no such file");
  if (std::filesystem::is_directory(status)) throw FileError(name, 0, 0, "is a directory, not a PNG file");

  std::ifstream in(file, std::ios::binary);
  if (!in) throw FileError(name, 0, 0, "cannot open: " + errno_text(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0);
  if (size < 0) throw FileError(name, 0, 0, "cannot read the file");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) throw FileError(name, 0, 0, "read failed");

  // stb_image would also decode JPEG, BMP, ...; goldens must be lossless, so insist on PNG.
  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < sizeof kSignature || !std::equal(std::begin(kSignature), std::end(kSignature), bytes.begin()))
    throw FileError(name, 0, 0, "not a PNG file (no PNG signature)");
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw FileError(name, 0, 0, "file too large");

  int w = 0, h = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &channels, 4), stbi_image_free);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw FileError(name, 0, 0, std::string("cannot decode the PNG: ") + (reason ? reason : "unknown reason"));
  }
  Image image(w, h);
  std::memcpy(image.rgba.data(), pixels.get(), image.rgba.size());
  return image;
}

ImageDiff compare_images(const Image& actual, const Image& expected, int tolerance) {
  check_image(actual, "compare_images (actual)");
  check_image(expected, "compare_images (expected)");
  if (tolerance < 0 || tolerance > 255)
    throw std::invalid_argument("compare_images: tolerance must be 0..255, got " + std::to_string(tolerance));

  ImageDiff diff;
  if (actual.width != expected.width || actual.height != expected.height) {
    // Nothing can be compared pixel for pixel: report the worst on every measure so that any
    // check a test makes fails, and show the actual image's frame all red.
    diff.same_size = false;
    diff.max_channel_delta = 255;
    diff.differing_pixels = std::max(pixel_count(actual), pixel_count(expected));
    diff.differing_fraction = 1.0;
    diff.rms = 255.0;
    diff.difference = Image(actual.width, actual.height);
    for (std::size_t i = 0; i < diff.difference.rgba.size(); i += 4) {
      diff.difference.rgba[i] = 255;
      diff.difference.rgba[i + 3] = 255;
    }
    return diff;
  }

  diff.same_size = true;
  diff.difference = Image(expected.width, expected.height);
  const std::size_t n = pixel_count(expected);
  std::uint64_t sum_sq = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint8_t* a = actual.rgba.data() + p * 4;
    const std::uint8_t* e = expected.rgba.data() + p * 4;
    int worst = 0;
    for (int c = 0; c < 4; ++c) {
      const int d = std::abs(int{a[c]} - int{e[c]});
      worst = std::max(worst, d);
      sum_sq += static_cast<std::uint64_t>(d * d);
    }
    diff.max_channel_delta = std::max(diff.max_channel_delta, worst);
    std::uint8_t* out = diff.difference.rgba.data() + p * 4;
    if (worst > tolerance) {
      ++diff.differing_pixels;
      out[0] = 255;
      out[1] = 0;
      out[2] = 0;
    } else {
      // The expected image as dim grey (Rec. 709 luma at a third of its brightness), so the
      // red stands out and the scene is still recognisable around it.
      const int luma = (2126 * e[0] + 7152 * e[1] + 722 * e[2]) / 10000;
      const auto grey = static_cast<std::uint8_t>(luma / 3);
      out[0] = out[1] = out[2] = grey;
    }
    out[3] = 255;
  }
  if (n > 0) {
    diff.differing_fraction = static_cast<double>(diff.differing_pixels) / static_cast<double>(n);
    diff.rms = std::sqrt(static_cast<double>(sum_sq) / static_cast<double>(n * 4));
  }
  return diff;
}

Image downsample(const Image& image, int factor) {
  check_image(image, "downsample");
  if (factor < 1) throw std::invalid_argument("downsample: factor must be >= 1, got " + std::to_string(factor));
  if (image.width % factor != 0 || image.height % factor != 0)
    throw std::invalid_argument("downsample: " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " is not a multiple of the factor " + std::to_string(factor));
  Image out(image.width / factor, image.height / factor);
  const auto box = static_cast<std::uint64_t>(factor) * static_cast<std::uint64_t>(factor);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      std::uint64_t sum[4] = {0, 0, 0, 0};
      for (int sy = 0; sy < factor; ++sy)
        for (int sx = 0; sx < factor; ++sx) {
          const std::uint8_t* p = image.at(x * factor + sx, y * factor + sy);
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
        }
      // Each channel on its own, alpha included (straight, not premultiplied: the renderer's
      // frames are opaque), in the stored 8-bit encoding; rounded to nearest, halves up.
      std::uint8_t* q = out.at(x, y);
      for (int c = 0; c < 4; ++c) q[c] = static_cast<std::uint8_t>((sum[c] + box / 2) / box);
    }
  }
  return out;
}

}  // namespace mallet::render
