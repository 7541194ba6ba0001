#pragma once
// Recorded camera frame streams for the tests: a tiny file format, and streams drawn by
// led_frame_synth (the one generator, shared with `mallet bench input`).
//
// The format: one text line, then per frame one text line and its bytes and a newline:
//   mallet-camera-stream 1
//   frame t_ns=4166667 sequence=1 width=160 height=120 format=grey bytes_per_line=0 size=19200 led=80.250,60.500
//   <size bytes as the camera sent them>\n
// `led` is the truth: the LED's centre at mid-exposure in pixels (pixel centres at integer
// coordinates), or `none` when the frame shows no LED. Fields in this order, one space apart.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "input/camera/camera_frame.hpp"
#include "input/camera/led_frame_synth.hpp"

namespace mallet::input::camera::test {

struct TruthPoint {
  double x = 0, y = 0;
};

//! One frame of a stream: what the camera sent, and where the LED truly was.
struct StreamFrame {
  Nanos t_ns = 0;
  std::uint32_t sequence = 0;
  int width = 0, height = 0;
  PixelFormat format = PixelFormat::grey;
  std::size_t bytes_per_line = 0;
  std::vector<std::uint8_t> bytes;
  std::optional<TruthPoint> led;
  //! The frame as a capture hands it over (a view of `bytes`).
  CameraFrame frame() const { return {t_ns, sequence, width, height, format, bytes_per_line, bytes}; }
};

//! The stream's file text (header, frames).
std::string format_frame_stream(const std::vector<StreamFrame>& frames);
//! Parses a stream; throws FileError "NAME: frame N at byte B: problem" (frame 0 = the
//! header line) for anything malformed.
std::vector<StreamFrame> parse_frame_stream(std::string_view data, const std::string& name);
//! Writes / reads a stream file (FileError when it cannot be written or read).
void write_frame_stream(const std::filesystem::path& path, const std::vector<StreamFrame>& frames);
std::vector<StreamFrame> read_frame_stream(const std::filesystem::path& path);

//! A generated stream: the LED moving in a straight line (or still), an optional second,
//! dimmer light that stays put, frames that the driver drops (their sequence numbers are
//! skipped) and frames where the LED is hidden.
struct StreamSpec {
  SynthScene scene;                 //!< size, background, noise, exposure; spots are set per frame
  PixelFormat format = PixelFormat::grey;
  std::size_t bytes_per_line = 0;   //!< GREY / YUYV rows, 0 = packed
  int frames = 30;                  //!< frames delivered
  double rate_hz = 240;
  std::uint32_t seed = 1;
  SynthSpot led;                    //!< at the first frame's mid-exposure; its velocity moves it
  std::optional<SynthSpot> reflection;
  std::vector<std::uint32_t> dropped;  //!< sequence numbers never delivered
  std::vector<std::uint32_t> hidden;   //!< sequence numbers delivered without the LED
};

//! A frame drawn packed as GREY, for tests that hand the finder luma directly.
struct LumaImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;
  LumaView view() const { return {width, height, pixels.data(), width, 1}; }
};
//! `scene` drawn by `synth`.
inline LumaImage draw(LedFrameSynth& synth, const SynthScene& scene) {
  LumaImage image{scene.width, scene.height, {}};
  synth.render(scene, image.pixels);
  return image;
}

//! The frames `spec` describes (throws std::runtime_error if an encoder refuses).
std::vector<StreamFrame> make_frame_stream(const StreamSpec& spec);

}  // namespace mallet::input::camera::test
