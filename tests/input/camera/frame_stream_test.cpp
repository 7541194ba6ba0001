// The camera stream files: written and read back, malformed ones refused with file and
// place, and the kept streams (README.md) decoded and tracked against their truth.
#include "input/camera/frame_stream.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/file_error.hpp"
#include "input/camera/frame_decode.hpp"
#include "input/camera/led_finder.hpp"

namespace mallet::input::camera::test {
namespace {

const std::filesystem::path kDir = std::filesystem::path(MALLET_TEST_SOURCE_DIR) / "tests/input/camera";

StreamSpec small_spec() {
  StreamSpec s;
  s.scene.width = 24;
  s.scene.height = 16;
  s.frames = 3;
  s.led = {10.5, 7.25, 1.2, 150};
  s.dropped = {1};
  s.hidden = {2};
  return s;
}

TEST(FrameStream, WrittenAndReadBack) {
  for (const PixelFormat f : {PixelFormat::grey, PixelFormat::yuyv, PixelFormat::mjpeg}) {
    StreamSpec spec = small_spec();
    spec.format = f;
    const std::vector<StreamFrame> made = make_frame_stream(spec);
    ASSERT_EQ(made.size(), 3u);
    EXPECT_EQ(made[1].sequence, 2u);  // sequence 1 dropped
    EXPECT_FALSE(made[1].led);        // sequence 2 hidden
    const std::vector<StreamFrame> back = parse_frame_stream(format_frame_stream(made), "x.stream");
    ASSERT_EQ(back.size(), made.size());
    for (std::size_t i = 0; i < made.size(); ++i) {
      EXPECT_EQ(back[i].t_ns, made[i].t_ns);
      EXPECT_EQ(back[i].sequence, made[i].sequence);
      EXPECT_EQ(back[i].format, f);
      EXPECT_EQ(back[i].bytes, made[i].bytes);
      ASSERT_EQ(back[i].led.has_value(), made[i].led.has_value());
      if (made[i].led) {
        EXPECT_NEAR(back[i].led->x, made[i].led->x, 5e-4);
      }
    }
  }
}

std::string error_of(const std::string& text) {
  try {
    parse_frame_stream(text, "bad.stream");
  } catch (const FileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(FrameStream, AMalformedFileIsOneLineNamingFileAndPlace) {
  const std::string good = format_frame_stream(make_frame_stream(small_spec()));
  const std::size_t second = good.find("\nframe ", good.find("\nframe ") + 1) + 1;  // the second frame's line
  EXPECT_EQ(error_of("P5 24 16\n"),
            "bad.stream: frame 0 at byte 0: not a camera stream (the first line must be \"mallet-camera-stream 1\")");
  std::string cut = good.substr(0, good.size() - 100);
  EXPECT_NE(error_of(cut).find("bad.stream: frame 3 at byte "), std::string::npos) << error_of(cut);
  EXPECT_NE(error_of(cut).find("runs past the end of the file"), std::string::npos) << error_of(cut);
  std::string fmt = good;
  fmt.replace(fmt.find("format=grey", second), 11, "format=rgb3");
  EXPECT_EQ(error_of(fmt), "bad.stream: frame 2 at byte " + std::to_string(second) +
                               ": format \"rgb3\": expected \"grey\", \"yuyv\" or \"mjpeg\"");
  std::string key = good;
  key.replace(key.find("width=", second), 6, "wide=");
  EXPECT_NE(error_of(key).find("frame 2 at byte " + std::to_string(second) + ": expected width="), std::string::npos)
      << error_of(key);
  std::string num = good;
  num.replace(num.find("sequence=", second), 10, "sequence=x");
  EXPECT_NE(error_of(num).find("sequence \"x"), std::string::npos) << error_of(num);
  for (const std::string& text : {cut, fmt, key, num}) EXPECT_EQ(error_of(text).find('\n'), std::string::npos);
  EXPECT_THROW(read_frame_stream(kDir / "no-such.stream"), FileError);
}

struct Tracked {
  int frames = 0, found = 0, dropped = 0;
  double worst_px = 0, sum2 = 0;
};

Tracked track(const std::string& file) {
  Tracked out;
  LedFinder finder;
  std::vector<std::uint8_t> scratch;
  std::optional<std::uint32_t> last_seq;
  for (const StreamFrame& sf : read_frame_stream(kDir / file)) {
    const CameraFrame frame = sf.frame();
    if (last_seq) out.dropped += static_cast<int>(frame.sequence - *last_seq - 1);
    last_seq = frame.sequence;
    ++out.frames;
    const auto luma = luma_view(frame, scratch);
    EXPECT_TRUE(luma) << file << " frame " << frame.sequence << ": " << luma.error();
    if (!luma) continue;
    const LedFind f = finder.find(*luma);
    EXPECT_EQ(f.led.has_value(), sf.led.has_value()) << file << " frame " << frame.sequence;
    if (!f.led || !sf.led) continue;
    ++out.found;
    const double e = std::hypot(f.led->x - sf.led->x, f.led->y - sf.led->y);
    out.worst_px = std::max(out.worst_px, e);
    out.sum2 += e * e;
  }
  return out;
}

TEST(CameraStreams, TheStillLedIsFoundWithinNoise) {
  const Tracked t = track("still_led.stream");
  EXPECT_EQ(t.frames, 30);
  EXPECT_EQ(t.found, 30);
  EXPECT_LT(std::sqrt(t.sum2 / t.found), 0.08);
  EXPECT_LT(t.worst_px, 0.2);
}

TEST(CameraStreams, TheMovingLedIsFollowedPastTheDimmerLightInMjpeg) {
  const Tracked t = track("moving_led.stream");
  EXPECT_EQ(t.frames, 40);
  EXPECT_EQ(t.found, 40);
  EXPECT_LT(t.worst_px, 0.3);  // the reflection is 18 px from the path at its nearest
}

TEST(CameraStreams, DroppedFramesAreGapsAndTrackingGoesOn) {
  const Tracked t = track("dropped_frames.stream");
  EXPECT_EQ(t.frames, 16);
  EXPECT_EQ(t.dropped, 5);
  EXPECT_EQ(t.found, 16);
  EXPECT_LT(t.worst_px, 0.3);
}

}  // namespace
}  // namespace mallet::input::camera::test
