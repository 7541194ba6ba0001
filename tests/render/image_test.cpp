// Images: PNG files round-trip bit for bit and are written atomically; unreadable files are
// reported by name; the golden comparison counts exactly the pixels beyond tolerance; the
// box filter gives the rounded mean.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/file_error.hpp"
#include "render/image.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

Image random_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  Image image(w, h);
  for (auto& b : image.rgba) b = static_cast<std::uint8_t>(byte(rng));
  return image;
}

Image filled(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = r;
      p[1] = g;
      p[2] = b;
      p[3] = a;
    }
  return image;
}

std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  return names;
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary);
  out << bytes;
}

TEST(ImagePng, RoundTripIsLosslessIncludingAlpha) {
  const auto dir = test::scratch_dir();
  const Image image = random_image(37, 23, 7);  // odd sizes: no row padding may creep in
  write_png(image, dir / "random.png");
  const Image back = read_png(dir / "random.png");
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 23);
  EXPECT_EQ(back.rgba, image.rgba);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"random.png"});  // no temporary left over
}

TEST(ImagePng, RewritingReplacesTheFileWhole) {
  const auto dir = test::scratch_dir();
  write_png(random_image(64, 64, 1), dir / "frame.png");
  const Image second = filled(3, 2, 10, 20, 30, 40);
  write_png(second, dir / "frame.png");
  EXPECT_EQ(read_png(dir / "frame.png").rgba, second.rgba);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"frame.png"});
}

TEST(ImagePng, WritingIntoAMissingFolderFailsNamingTheFile) {
  const auto file = test::scratch_dir() / "no-such-folder" / "out.png";
  try {
    write_png(filled(2, 2, 1, 2, 3, 4), file);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(file.parent_path()));  // not created behind our back
}

TEST(ImagePng, AnImageWhoseBufferDoesNotMatchItsSizeIsRefused) {
  Image broken(4, 4);
  broken.rgba.pop_back();
  EXPECT_THROW(write_png(broken, test::scratch_dir() / "broken.png"), std::invalid_argument);
}

TEST(ImagePng, AMissingFileIsReportedByName) {
  const auto file = test::scratch_dir() / "absent.png";
  const FileError e = test::file_error_of([&] { read_png(file); });
  EXPECT_EQ(e.file(), file.string());
  EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
}

TEST(ImagePng, GarbageIsReportedByNameAndReason) {
  const auto dir = test::scratch_dir();
  write_bytes(dir / "text.png", "this is not an image at all");
  const FileError text = test::file_error_of([&] { read_png(dir / "text.png"); });
  EXPECT_EQ(text.file(), (dir / "text.png").string());
  EXPECT_NE(std::string(text.what()).find("not a PNG"), std::string::npos) << text.what();

  // A real PNG cut short: the signature is right, the data is not.
  write_png(random_image(32, 32, 3), dir / "whole.png");
  std::ifstream in(dir / "whole.png", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_bytes(dir / "cut.png", bytes.substr(0, bytes.size() / 2));
  const FileError cut = test::file_error_of([&] { read_png(dir / "cut.png"); });
  EXPECT_EQ(cut.file(), (dir / "cut.png").string());
  EXPECT_NE(std::string(cut.what()).find("cannot decode"), std::string::npos) << cut.what();
}

TEST(ImageCompare, IdenticalImagesDoNotDiffer) {
  const Image image = random_image(16, 9, 4);
  const ImageDiff d = compare_images(image, image, 0);
  EXPECT_TRUE(d.same_size);
  EXPECT_EQ(d.max_channel_delta, 0);
  EXPECT_EQ(d.differing_pixels, 0u);
  EXPECT_EQ(d.differing_fraction, 0.0);
  EXPECT_EQ(d.rms, 0.0);
  EXPECT_EQ(d.difference.width, 16);
  EXPECT_EQ(d.difference.height, 9);
}

TEST(ImageCompare, CountsExactlyThePixelsBeyondTolerance) {
  constexpr int kTolerance = 3;
  const Image expected = filled(4, 3, 100, 100, 100, 255);
  Image actual = expected;
  actual.at(0, 0)[0] = 100 + kTolerance;      // at the tolerance: agrees
  actual.at(1, 0)[1] = 100 - kTolerance;      // at the tolerance, below: agrees
  actual.at(2, 0)[2] = 100 + kTolerance + 1;  // one beyond: differs
  actual.at(3, 1)[3] = 255 - kTolerance - 1;  // alpha counts too: differs
  actual.at(1, 2)[0] = 150;                   // two channels off, one pixel
  actual.at(1, 2)[1] = 80;

  const ImageDiff d = compare_images(actual, expected, kTolerance);
  EXPECT_TRUE(d.same_size);
  EXPECT_EQ(d.differing_pixels, 3u);
  EXPECT_DOUBLE_EQ(d.differing_fraction, 3.0 / 12.0);
  EXPECT_EQ(d.max_channel_delta, 50);
  const double sum_sq = 3 * 3 + 3 * 3 + 4 * 4 + 4 * 4 + 50 * 50 + 20 * 20;
  EXPECT_NEAR(d.rms, std::sqrt(sum_sq / (12 * 4)), 1e-12);

  // The picture: red exactly where differing, the expected image in dim grey elsewhere.
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const std::uint8_t* p = d.difference.at(x, y);
      const bool differs = (x == 2 && y == 0) || (x == 3 && y == 1) || (x == 1 && y == 2);
      SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
      if (differs) {
        EXPECT_EQ(p[0], 255);
        EXPECT_EQ(p[1], 0);
        EXPECT_EQ(p[2], 0);
      } else {
        EXPECT_EQ(p[0], p[1]);
        EXPECT_EQ(p[1], p[2]);
        EXPECT_LT(p[0], 100);  // dimmed
      }
      EXPECT_EQ(p[3], 255);
    }

  // One step stricter and the pixels at the boundary differ too.
  EXPECT_EQ(compare_images(actual, expected, kTolerance - 1).differing_pixels, 5u);
  // Loose enough and nothing differs, while the deltas are still reported.
  const ImageDiff loose = compare_images(actual, expected, 50);
  EXPECT_EQ(loose.differing_pixels, 0u);
  EXPECT_EQ(loose.max_channel_delta, 50);
}

TEST(ImageCompare, DifferentSizesDifferEverywhere) {
  const ImageDiff d = compare_images(filled(4, 4, 0, 0, 0, 255), filled(4, 5, 0, 0, 0, 255), 255);
  EXPECT_FALSE(d.same_size);
  EXPECT_EQ(d.differing_fraction, 1.0);
  EXPECT_EQ(d.differing_pixels, 20u);
  EXPECT_EQ(d.max_channel_delta, 255);
  ASSERT_EQ(d.difference.width, 4);  // the actual image's frame, all red
  ASSERT_EQ(d.difference.height, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const std::uint8_t* p = d.difference.at(x, y);
      EXPECT_EQ(p[0], 255);
      EXPECT_EQ(p[1], 0);
      EXPECT_EQ(p[2], 0);
      EXPECT_EQ(p[3], 255);
    }
}

TEST(ImageCompare, ToleranceOutsideTheByteRangeIsRefused) {
  const Image image(2, 2);
  EXPECT_THROW(compare_images(image, image, -1), std::invalid_argument);
  EXPECT_THROW(compare_images(image, image, 256), std::invalid_argument);
}

TEST(ImageDownsample, CheckerboardGivesTheExactMean) {
  // A 1-pixel checkerboard of two colours, alpha alternating too: every 2×2 box holds two
  // of each, so the mean is the midpoint; 0/255 averages to 127.5, which rounds up.
  Image board(8, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool odd = (x + y) % 2 == 1;
      std::uint8_t* p = board.at(x, y);
      p[0] = odd ? 10 : 30;
      p[1] = odd ? 0 : 255;
      p[2] = odd ? 200 : 100;
      p[3] = odd ? 255 : 0;
    }
  const Image small = downsample(board, 2);
  ASSERT_EQ(small.width, 4);
  ASSERT_EQ(small.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const std::uint8_t* p = small.at(x, y);
      EXPECT_EQ(p[0], 20);
      EXPECT_EQ(p[1], 128);
      EXPECT_EQ(p[2], 150);
      EXPECT_EQ(p[3], 128);
    }
}

TEST(ImageDownsample, RoundsToNearest) {
  // 3×3 boxes: a sum of 4 (mean 0.44) rounds down, 5 (0.56) rounds up; 255·9 stays 255.
  Image image(6, 3);
  for (int i = 0; i < 4; ++i) image.at(i % 3, i / 3)[0] = 1;
  for (int i = 0; i < 5; ++i) image.at(3 + i % 3, i / 3)[0] = 1;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 6; ++x) image.at(x, y)[3] = 255;
  const Image small = downsample(image, 3);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_EQ(small.at(0, 0)[0], 0);
  EXPECT_EQ(small.at(1, 0)[0], 1);
  EXPECT_EQ(small.at(0, 0)[3], 255);
  EXPECT_EQ(small.at(1, 0)[3], 255);
}

TEST(ImageDownsample, FactorOneIsTheIdentityAndNonMultiplesAreRefused) {
  const Image image = random_image(6, 4, 9);
  EXPECT_EQ(downsample(image, 1).rgba, image.rgba);
  EXPECT_THROW(downsample(image, 4), std::invalid_argument);  // 6 is not a multiple of 4
  EXPECT_THROW(downsample(image, 3), std::invalid_argument);  // 4 is not a multiple of 3
  EXPECT_THROW(downsample(image, 0), std::invalid_argument);
}

}  // namespace
}  // namespace mallet::render
