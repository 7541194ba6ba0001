#include "render/gpu_resources.hpp"

#include <cstring>

#include "render/vk_error.hpp"

namespace mallet::render {

GpuBuffer make_host_buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  VkDevice dev = ctx.device();
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size > 0 ? size : 4;
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer raw;
  check(vkCreateBuffer(dev, &bci, nullptr, &raw), "creating a buffer");
  GpuBuffer out;
  out.buffer = vk::Buffer(dev, raw);
  out.size = bci.size;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(dev, raw, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory mem;
  check(vkAllocateMemory(dev, &mai, nullptr, &mem), "allocating buffer memory");
  out.memory = vk::Memory(dev, mem, mai.allocationSize);
  check(vkBindBufferMemory(dev, raw, mem, 0), "binding buffer memory");
  check(vkMapMemory(dev, mem, 0, VK_WHOLE_SIZE, 0, &out.mapped), "mapping buffer memory");
  return out;
}

GpuBuffer make_host_buffer(const Context& ctx, std::span<const std::byte> data, VkBufferUsageFlags usage) {
  GpuBuffer out = make_host_buffer(ctx, data.size(), usage);
  if (!data.empty()) std::memcpy(out.mapped, data.data(), data.size());
  return out;
}

GpuImage make_image(const Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                    VkSampleCountFlagBits samples, VkImageAspectFlags aspect) {
  VkDevice dev = ctx.device();
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = format;
  ici.extent = {extent.width, extent.height, 1};
  ici.mipLevels = 1;
  ici.arrayLayers = 1;
  ici.samples = samples;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage raw;
  check(vkCreateImage(dev, &ici, nullptr, &raw), "creating an image");
  GpuImage out;
  out.image = vk::Image(dev, raw);
  out.format = format;
  out.extent = extent;
  out.samples = samples;
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(dev, raw, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkDeviceMemory mem;
  check(vkAllocateMemory(dev, &mai, nullptr, &mem), "allocating image memory");
  out.memory = vk::Memory(dev, mem, mai.allocationSize);
  check(vkBindImageMemory(dev, raw, mem, 0), "binding image memory");
  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = raw;
  vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vci.format = format;
  vci.subresourceRange = {aspect, 0, 1, 0, 1};
  VkImageView view;
  check(vkCreateImageView(dev, &vci, nullptr, &view), "creating an image view");
  out.view = vk::ImageView(dev, view);
  return out;
}

GpuImage make_texture(const Context& ctx, VkExtent2D extent, VkFormat format,
                      std::span<const std::uint8_t> pixels, std::uint32_t bytes_per_pixel) {
  const VkDeviceSize size = VkDeviceSize{extent.width} * extent.height * bytes_per_pixel;
  if (pixels.size() != size) throw RenderError("texture data does not match its size");
  GpuImage tex = make_image(ctx, extent, format, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                            VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
  GpuBuffer staging = make_host_buffer(ctx, std::as_bytes(pixels), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    transition(cmd, tex.image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer.get(), tex.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &region);
    transition(cmd, tex.image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  return tex;
}

void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace mallet::render
