#include "render/gpu_resources.hpp"

#include <cstring>

#include "render/vk_error.hpp"

namespace mallet::render {

namespace {

//! Memory for `req` of a type with `properties`, owned and counted from the moment it exists.
vk::Memory allocate(const Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags properties,
                    const char* what) {
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, properties);
  VkDeviceMemory mem;
  check(vkAllocateMemory(ctx.device(), &mai, nullptr, &mem), what);
  return vk::Memory(ctx.device(), mem, {mai.allocationSize});
}

}  // namespace

vk::ImageView make_image_view(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                              const char* what) {
  const VkImageViewCreateInfo vci{.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = image,
                                  .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                  .subresourceRange = {aspect, 0, 1, 0, 1}};
  VkImageView view;
  check(vkCreateImageView(device, &vci, nullptr, &view), what);
  return vk::ImageView(device, view);
}

GpuBuffer make_host_buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  VkDevice dev = ctx.device();
  const VkBufferCreateInfo bci{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size > 0 ? size : 4,
                               .usage = usage, .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  VkBuffer raw;
  check(vkCreateBuffer(dev, &bci, nullptr, &raw), "creating a buffer");
  GpuBuffer out;
  out.buffer = vk::Buffer(dev, raw);
  out.size = bci.size;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(dev, raw, &req);
  out.memory = allocate(ctx, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                        "allocating buffer memory");
  check(vkBindBufferMemory(dev, raw, out.memory.get(), 0), "binding buffer memory");
  check(vkMapMemory(dev, out.memory.get(), 0, VK_WHOLE_SIZE, 0, &out.mapped), "mapping buffer memory");
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
  const VkImageCreateInfo ici{.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                              .format = format, .extent = {extent.width, extent.height, 1}, .mipLevels = 1,
                              .arrayLayers = 1, .samples = samples, .tiling = VK_IMAGE_TILING_OPTIMAL,
                              .usage = usage, .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
                              .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  VkImage raw;
  check(vkCreateImage(dev, &ici, nullptr, &raw), "creating an image");
  GpuImage out;
  out.image = vk::Image(dev, raw);
  out.format = format;
  out.extent = extent;
  out.samples = samples;
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(dev, raw, &req);
  out.memory = allocate(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "allocating image memory");
  check(vkBindImageMemory(dev, raw, out.memory.get(), 0), "binding image memory");
  out.view = make_image_view(dev, raw, format, aspect, "creating an image view");
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
    record_texture_upload(cmd, staging.buffer.get(), tex.image.get(), extent, VK_IMAGE_LAYOUT_UNDEFINED,
                          VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
  });
  return tex;
}

void record_texture_upload(VkCommandBuffer cmd, VkBuffer staging, VkImage image, VkExtent2D extent,
                           VkImageLayout from, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access) {
  transition(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, from, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, src_stage,
             src_access, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyBufferToImage(cmd, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  transition(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
             VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  const VkImageMemoryBarrier2 b{.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
                                .srcStageMask = src_stage, .srcAccessMask = src_access,
                                .dstStageMask = dst_stage, .dstAccessMask = dst_access,
                                .oldLayout = from, .newLayout = to,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .image = image, .subresourceRange = {aspect, 0, 1, 0, 1}};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace mallet::render
