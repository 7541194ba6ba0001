// A size in pixels as the flags write it: WIDTHxHEIGHT, each side in range, with the
// parser's own wording for what is wrong.
#include <gtest/gtest.h>

#include "core/pixel_size.hpp"

namespace mallet {
namespace {

TEST(PixelSize, WidthByHeightInDigits) {
  const auto s = parse_pixel_size("1280x720");
  ASSERT_TRUE(s) << s.error();
  EXPECT_EQ(s->width, 1280u);
  EXPECT_EQ(s->height, 720u);
  EXPECT_EQ(parse_pixel_size("16x8192")->height, 8192u);
}

TEST(PixelSize, AnythingElseIsRefusedWithTheTextQuoted) {
  for (const char* bad : {"", "1280", "1280x", "x720", "1280*720", "-1x720", "12.5x720", "1280x720 ", "123456x720"}) {
    const auto s = parse_pixel_size(bad);
    ASSERT_FALSE(s) << bad;
    EXPECT_EQ(s.error(), std::string("expected WIDTHxHEIGHT such as 1280x720, got \"") + bad + "\"");
  }
}

TEST(PixelSize, SidesOutsideTheRangeAreRefused) {
  EXPECT_EQ(parse_pixel_size("15x720").error(), "width and height must be 16..8192, got 15x720");
  EXPECT_EQ(parse_pixel_size("1280x8193").error(), "width and height must be 16..8192, got 1280x8193");
  EXPECT_TRUE(parse_pixel_size("2x2", 1, 4));
}

}  // namespace
}  // namespace mallet
