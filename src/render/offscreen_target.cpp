#include "render/offscreen_target.hpp"

#include <cstring>
#include <utility>

#include "render/vk_error.hpp"

namespace mallet::render {

OffscreenTarget::OffscreenTarget(const Context& ctx, VkExtent2D extent, VkFormat format) : ctx_(ctx), extent_(extent) {
  if (extent.width == 0 || extent.height == 0 || extent.width > 16384 || extent.height > 16384)
    throw RenderError("image size " + std::to_string(extent.width) + "x" + std::to_string(extent.height) +
                      " is out of range (1..16384)");
  if (format != kFormat && format != VK_FORMAT_B8G8R8A8_SRGB)
    throw RenderError("an offscreen image is RGBA8 or BGRA8 (sRGB)");
  color_ = make_image(ctx, extent, format,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                          VK_IMAGE_USAGE_TRANSFER_DST_BIT,  // the renderer's background is copied in
                      VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  // The copy's rows start on the device's optimal copy alignment, so the pitch may be
  // wider than the row; read_back() honours it.
  const VkDeviceSize align = std::max<VkDeviceSize>(ctx.properties().limits.optimalBufferCopyRowPitchAlignment, 4);
  row_pitch_ = (VkDeviceSize{extent.width} * 4 + align - 1) / align * align;
  readback_ = make_host_buffer(ctx, row_pitch_ * extent.height, VK_BUFFER_USAGE_TRANSFER_DST_BIT);

  cmd_ = ctx.allocate_command_buffer();
  fence_ = ctx.make_fence();
}

OffscreenTarget::~OffscreenTarget() {
  vkDeviceWaitIdle(ctx_.device());
  ctx_.free_command_buffer(cmd_);
}

void OffscreenTarget::draw(SceneRenderer& renderer, const FrameState& state) {
  check(vkResetCommandBuffer(cmd_, 0), "resetting a command buffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd_, &bi), "beginning a command buffer");
  renderer.record(cmd_,
                  {color_.image.get(), color_.view.get(), extent_, true, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, keep_ && drawn_,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
                  state, 0);
  // A kept frame changed only the renderer's drawn area; the host copy holds the rest.
  const PixelRect whole{0, 0, static_cast<int>(extent_.width), static_cast<int>(extent_.height)};
  changed_ = keep_ && drawn_ ? intersection(renderer.last_drawn_area(), whole) : whole;
  drawn_ = true;
  VkBufferImageCopy region{};
  region.bufferOffset = static_cast<VkDeviceSize>(changed_.y0) * row_pitch_ + static_cast<VkDeviceSize>(changed_.x0) * 4;
  region.bufferRowLength = static_cast<std::uint32_t>(row_pitch_ / 4);
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageOffset = {changed_.x0, changed_.y0, 0};
  region.imageExtent = {static_cast<std::uint32_t>(changed_.x1 - changed_.x0),
                        static_cast<std::uint32_t>(changed_.y1 - changed_.y0), 1};
  if (!changed_.empty())
    vkCmdCopyImageToBuffer(cmd_, color_.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer.get(), 1,
                           &region);
  VkMemoryBarrier2 host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
  host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &host;
  vkCmdPipelineBarrier2(cmd_, &dep);
  check(vkEndCommandBuffer(cmd_), "ending a command buffer");

  VkFence f = fence_.get();
  check(vkResetFences(ctx_.device(), 1, &f), "resetting a fence");
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd_;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  check(vkQueueSubmit2(ctx_.queue(), 1, &si, f), "submitting a frame");
  check(vkWaitForFences(ctx_.device(), 1, &f, VK_TRUE, UINT64_MAX), "waiting for a frame");
}

Image OffscreenTarget::read_back() const {
  Image out(static_cast<int>(extent_.width), static_cast<int>(extent_.height));
  const auto* src = static_cast<const std::uint8_t*>(readback_.mapped);
  const std::size_t row = std::size_t{extent_.width} * 4;
  for (std::uint32_t y = 0; y < extent_.height; ++y)
    std::memcpy(out.rgba.data() + y * row, src + y * row_pitch_, row);
  if (color_.format == VK_FORMAT_B8G8R8A8_SRGB)
    for (std::size_t i = 0; i < out.rgba.size(); i += 4) std::swap(out.rgba[i], out.rgba[i + 2]);
  return out;
}

Image OffscreenTarget::render(SceneRenderer& renderer, const FrameState& state) {
  draw(renderer, state);
  return read_back();
}

}  // namespace mallet::render
