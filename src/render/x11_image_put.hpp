#pragma once
// Showing a CPU rasteriser's frames in an X11 window by putting only the pixels that
// changed (XPutImage of one rectangle), where Vulkan's own presentation would send the
// whole picture each frame.
//
// Why: Mesa's software presentation (lavapipe, Mesa 22.3) hands every frame to the X
// server with xcb_put_image of the whole image through the X socket, unless the server also
// has DRI3, which Xvfb and Xwayland without a GPU lack. At 1920×1080 that is 8.3 MB a frame,
// half a gigabyte a second at 60 frames: measured with perf in the attract mode, 45 % of the
// kiosk's CPU samples were the kernel copying it into the socket, and the X server spent as
// much again reading it. A frame of the kiosk changes 2–6 % of the image (the mallet, its
// shadow, a lit bar, the overlay's text: render/frame_damage.hpp), and only that is sent.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "core/result.hpp"
#include "render/scene_view.hpp"

struct GLFWwindow;

namespace mallet::render {

class X11ImagePut {
 public:
  //! For `window` when it is an X11 window whose pixels are 32 bits of B, G, R and a
  //! padding or alpha byte (a TrueColor visual of depth 24 or 32 with red 0xff0000, green
  //! 0xff00 and blue 0xff: every X server on a PC), which is how the frames are drawn
  //! (VK_FORMAT_B8G8R8A8_SRGB). Otherwise why not, in a few words.
  static Result<std::unique_ptr<X11ImagePut>, std::string> open(GLFWwindow* window);
  ~X11ImagePut();
  X11ImagePut(const X11ImagePut&) = delete;
  X11ImagePut& operator=(const X11ImagePut&) = delete;

  //! Puts `area` of the picture `pixels` (`width` × `height`, rows `row_bytes` apart,
  //! B8G8R8A8) at the same place in the window, and sends it to the server at once.
  void put(const std::uint8_t* pixels, int width, int height, std::size_t row_bytes, PixelRect area);
  //! Pixels put since open(), for the benchmark's and the tests' account.
  std::uint64_t pixels_put() const { return pixels_put_; }

 private:
  struct Native;
  explicit X11ImagePut(std::unique_ptr<Native> native);
  std::unique_ptr<Native> native_;
  std::uint64_t pixels_put_ = 0;
};

}  // namespace mallet::render
