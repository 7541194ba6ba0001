// frame_decode: GREY and YUYV read in place with their row stride, MJPEG decoded by libjpeg,
// and every frame that does not add up refused with one line.
#include "input/camera/frame_decode.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <numeric>

#include "input/camera/frame_stream.hpp"
#include "input/camera/led_frame_synth.hpp"

namespace mallet::input::camera {
namespace {

std::vector<std::uint8_t> ramp(int w, int h) {
  std::vector<std::uint8_t> v(static_cast<std::size_t>(w * h));
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<std::uint8_t>((i * 37 + 11) % 251);
  return v;
}

CameraFrame frame_of(const std::vector<std::uint8_t>& bytes, int w, int h, PixelFormat f, std::size_t bpl = 0) {
  return {0, 0, w, h, f, bpl, bytes};
}

void expect_same_luma(const LumaView& v, const std::vector<std::uint8_t>& luma) {
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x)
      ASSERT_EQ(v.at(x, y), luma[static_cast<std::size_t>(y * v.width + x)]) << "at " << x << "," << y;
}

TEST(LumaView, GreyIsReadInPlace) {
  const std::vector<std::uint8_t> luma = ramp(7, 5);
  std::vector<std::uint8_t> scratch;
  const auto v = luma_view(frame_of(luma, 7, 5, PixelFormat::grey), scratch);
  ASSERT_TRUE(v) << v.error();
  EXPECT_EQ(v->data, luma.data());
  EXPECT_EQ(v->row_stride, 7);
  EXPECT_EQ(v->pixel_step, 1);
  EXPECT_TRUE(scratch.empty());
  expect_same_luma(*v, luma);
}

TEST(LumaView, GreyHonoursBytesPerLine) {
  const std::vector<std::uint8_t> luma = ramp(5, 4);
  auto bytes = encode_frame(luma, 5, 4, PixelFormat::grey, 8);
  ASSERT_TRUE(bytes);
  ASSERT_EQ(bytes->size(), 32u);
  std::vector<std::uint8_t> scratch;
  // The padding holds junk a wrong stride would read.
  for (std::size_t y = 0; y < 4; ++y)
    for (std::size_t x = 5; x < 8; ++x) (*bytes)[y * 8 + x] = 0xEE;
  const auto v = luma_view(frame_of(*bytes, 5, 4, PixelFormat::grey, 8), scratch);
  ASSERT_TRUE(v) << v.error();
  EXPECT_EQ(v->row_stride, 8);
  expect_same_luma(*v, luma);
  // The last row without its padding is still a whole frame.
  bytes->resize(29);
  EXPECT_TRUE(luma_view(frame_of(*bytes, 5, 4, PixelFormat::grey, 8), scratch));
  bytes->resize(28);
  EXPECT_FALSE(luma_view(frame_of(*bytes, 5, 4, PixelFormat::grey, 8), scratch));
}

TEST(LumaView, YuyvReadsTheYBytesWithTheirStride) {
  const std::vector<std::uint8_t> luma = ramp(6, 3);
  const auto bytes = encode_frame(luma, 6, 3, PixelFormat::yuyv, 16);
  ASSERT_TRUE(bytes);
  std::vector<std::uint8_t> scratch;
  const auto v = luma_view(frame_of(*bytes, 6, 3, PixelFormat::yuyv, 16), scratch);
  ASSERT_TRUE(v) << v.error();
  EXPECT_EQ(v->pixel_step, 2);
  EXPECT_EQ(v->row_stride, 16);
  EXPECT_EQ(v->data, bytes->data());
  expect_same_luma(*v, luma);
}

TEST(LumaView, AShortBufferIsOneLine) {
  const std::vector<std::uint8_t> bytes(1000, 0);
  std::vector<std::uint8_t> scratch;
  const auto v = luma_view(frame_of(bytes, 640, 480, PixelFormat::yuyv), scratch);
  ASSERT_FALSE(v);
  EXPECT_EQ(v.error(), "a 640x480 yuyv frame needs 614400 bytes, this one has 1000");
  const auto g = luma_view(frame_of(bytes, 640, 480, PixelFormat::grey), scratch);
  ASSERT_FALSE(g);
  EXPECT_EQ(g.error(), "a 640x480 grey frame needs 307200 bytes, this one has 1000");
}

TEST(LumaView, AStrideShorterThanARowOrAnEmptySizeIsRefused) {
  const std::vector<std::uint8_t> bytes(4096, 0);
  std::vector<std::uint8_t> scratch;
  const auto s = luma_view(frame_of(bytes, 32, 8, PixelFormat::yuyv, 40), scratch);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error(), "a 32x8 yuyv frame: bytes_per_line 40 is less than a row's 64 bytes");
  const auto z = luma_view(frame_of(bytes, 0, 8, PixelFormat::grey), scratch);
  ASSERT_FALSE(z);
  EXPECT_NE(z.error().find("width and height must be"), std::string::npos) << z.error();
}

TEST(LumaView, MjpegIsDecodedToLumaInTheScratch) {
  LedFrameSynth synth(3);
  SynthScene scene;
  scene.width = 64;
  scene.height = 48;
  scene.spots.push_back({30.4, 20.7, 2.0, 200});
  std::vector<std::uint8_t> luma;
  synth.render(scene, luma);
  const auto jpeg = encode_frame(luma, 64, 48, PixelFormat::mjpeg, 0, 95);
  ASSERT_TRUE(jpeg) << jpeg.error();
  std::vector<std::uint8_t> scratch;
  const auto v = luma_view(frame_of(*jpeg, 64, 48, PixelFormat::mjpeg), scratch);
  ASSERT_TRUE(v) << v.error();
  EXPECT_EQ(v->data, scratch.data());
  EXPECT_EQ(v->pixel_step, 1);
  EXPECT_EQ(v->row_stride, 64);
  double abs_err = 0;
  int worst = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const int d = std::abs(v->at(x, y) - luma[static_cast<std::size_t>(y * 64 + x)]);
      abs_err += d;
      worst = std::max(worst, d);
    }
  EXPECT_LT(abs_err / (64 * 48), 1.5);  // quality 95: a level or so on average
  EXPECT_LT(worst, 24);
  // A second frame reuses the scratch (no allocation per frame).
  const std::uint8_t* before = scratch.data();
  ASSERT_TRUE(luma_view(frame_of(*jpeg, 64, 48, PixelFormat::mjpeg), scratch));
  EXPECT_EQ(scratch.data(), before);
}

TEST(LumaView, AJpegOfAnotherSizeIsRefused) {
  const auto jpeg = encode_frame(ramp(32, 16), 32, 16, PixelFormat::mjpeg);
  ASSERT_TRUE(jpeg);
  std::vector<std::uint8_t> scratch;
  const auto v = luma_view(frame_of(*jpeg, 64, 16, PixelFormat::mjpeg), scratch);
  ASSERT_FALSE(v);
  EXPECT_EQ(v.error(), "mjpeg frame is 32x16, the camera said 64x16");
}

TEST(LumaView, ACorruptJpegIsAnErrorNotAnExit) {
  std::vector<std::uint8_t> scratch;
  const std::vector<std::uint8_t> junk = ramp(40, 10);
  const auto a = luma_view(frame_of(junk, 640, 480, PixelFormat::mjpeg), scratch);
  ASSERT_FALSE(a);
  EXPECT_EQ(a.error().rfind("mjpeg frame: ", 0), 0u) << a.error();
  EXPECT_EQ(a.error().find('\n'), std::string::npos);

  // Cut short: libjpeg would fill the rest with grey and warn; a warning is an error here.
  auto jpeg = encode_frame(ramp(64, 64), 64, 64, PixelFormat::mjpeg);
  ASSERT_TRUE(jpeg);
  jpeg->resize(jpeg->size() / 2);
  const auto b = luma_view(frame_of(*jpeg, 64, 64, PixelFormat::mjpeg), scratch);
  ASSERT_FALSE(b);
  EXPECT_EQ(b.error().rfind("mjpeg frame: ", 0), 0u) << b.error();

  const std::vector<std::uint8_t> none;
  const auto c = luma_view(frame_of(none, 64, 64, PixelFormat::mjpeg), scratch);
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error(), "mjpeg frame: empty (64x64 expected)");
}

}  // namespace
}  // namespace mallet::input::camera
