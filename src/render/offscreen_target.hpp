#pragma once
// Rendering into an image in memory: the golden tests, `mallet render`, the benchmark,
// the headless kiosk, and a CPU rasteriser's X11 window (render/x11_image_put.hpp). The
// colour image is sRGB RGBA8 (or BGRA8, an X server's order), copied after each frame into
// a host buffer and from there, row by row at the copy's row pitch, into an Image.
#include <vulkan/vulkan.h>

#include "render/gpu_resources.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

namespace mallet::render {

class OffscreenTarget {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_SRGB;

  //! `format`: kFormat, or VK_FORMAT_B8G8R8A8_SRGB (pixels() then in an X server's order;
  //! read_back() still gives RGBA).
  OffscreenTarget(const Context& ctx, VkExtent2D extent, VkFormat format = kFormat);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  //! Draws one frame and waits for it; the pixels are then in image().
  void draw(SceneRenderer& renderer, const FrameState& state);
  //! Draws one frame, waits, and copies the pixels out.
  Image render(SceneRenderer& renderer, const FrameState& state);
  //! The pixels of the last frame drawn.
  Image read_back() const;

  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return color_.format; }
  //! Each frame drawn over the one before, as a window's swapchain images are: only what
  //! changed since is drawn (FrameTarget::kept), and only that is copied out (the host
  //! copy keeps the rest from the frames before). Off by default: every frame whole.
  void keep_frames(bool keep) { keep_ = keep; }
  //! The next frame is drawn and copied out whole (kept frames: nothing is known of the
  //! image's pixels any more, or a picture must be shown whole again).
  void draw_whole() { drawn_ = false; }
  //! The pixels the last draw() changed (the whole image unless frames are kept).
  PixelRect changed() const { return changed_; }
  //! The host copy of the image: extent().height rows of row_pitch() bytes, 4 per pixel in
  //! format()'s order, as of the last draw().
  const std::uint8_t* pixels() const { return static_cast<const std::uint8_t*>(readback_.mapped); }
  VkDeviceSize row_pitch() const { return row_pitch_; }

 private:
  const Context& ctx_;
  VkExtent2D extent_;
  GpuImage color_;
  GpuBuffer readback_;
  VkDeviceSize row_pitch_ = 0;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  vk::Fence fence_;
  bool keep_ = false, drawn_ = false;
  PixelRect changed_;
};

}  // namespace mallet::render
