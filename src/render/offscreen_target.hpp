#pragma once
// Rendering into an image in memory: the golden tests, `mallet render`, the benchmark
// and the headless kiosk. The colour image is sRGB RGBA8, copied after each frame into
// a host buffer and from there, row by row at the copy's row pitch, into an Image.
#include <vulkan/vulkan.h>

#include "render/gpu_resources.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

namespace mallet::render {

class OffscreenTarget {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_SRGB;

  OffscreenTarget(const Context& ctx, VkExtent2D extent);
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
  //! Each frame drawn over the one before, as a window's swapchain images are: only what
  //! changed since is drawn (FrameTarget::kept). Off by default: every frame whole.
  void keep_frames(bool keep) { keep_ = keep; }

 private:
  const Context& ctx_;
  VkExtent2D extent_;
  GpuImage color_;
  GpuBuffer readback_;
  VkDeviceSize row_pitch_ = 0;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  vk::Fence fence_;
  bool keep_ = false, drawn_ = false;
};

}  // namespace mallet::render
