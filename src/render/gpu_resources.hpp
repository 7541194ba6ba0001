#pragma once
// Buffers and images with their memory, owned together, and the one image-layout
// barrier helper (synchronization2) the renderer uses everywhere.
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "render/vk_context.hpp"

namespace mallet::render {

struct GpuBuffer {
  vk::Buffer buffer;
  vk::Memory memory;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  //!< host-visible buffers stay mapped for their lifetime
};

//! A host-visible, coherent, persistently mapped buffer. Vertex and index data live in
//! such buffers too: the scene is a few thousand vertices, uploaded once.
GpuBuffer make_host_buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
GpuBuffer make_host_buffer(const Context& ctx, std::span<const std::byte> data, VkBufferUsageFlags usage);

struct GpuImage {
  vk::Image image;
  vk::Memory memory;
  vk::ImageView view;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

//! A 2D view of one level and layer of `image` (`what` names the step in an error).
vk::ImageView make_image_view(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                              const char* what);

GpuImage make_image(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                    VkSampleCountFlagBits samples, VkImageAspectFlags aspect);

//! A sampled texture filled with `pixels` (tightly packed, `bytes_per_pixel` each) and
//! left in SHADER_READ_ONLY_OPTIMAL.
GpuImage make_texture(const Context& ctx, VkExtent2D extent, VkFormat format,
                      std::span<const std::uint8_t> pixels, std::uint32_t bytes_per_pixel);

//! Records a whole texture's texels copied from `staging` (tightly packed) into `image`: from
//! `from` (what the earlier commands left it as, after their `src_stage`/`src_access`) to
//! TRANSFER_DST, the copy, then SHADER_READ_ONLY_OPTIMAL for fragment shaders.
void record_texture_upload(VkCommandBuffer cmd, VkBuffer staging, VkImage image, VkExtent2D extent,
                           VkImageLayout from, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access);

//! Records a layout transition with a full synchronization2 barrier between the given
//! stages/accesses.
void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

}  // namespace mallet::render
