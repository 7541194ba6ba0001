#pragma once
// One RAII owner per kind of Vulkan object: a move-only handle that destroys its object
// with the right vkDestroy*/vkFree* call for its kind, on the device that made it.
#include <utility>

#include <vulkan/vulkan.h>

namespace mallet::render {

template <typename Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class DeviceOwned {
 public:
  DeviceOwned() = default;
  DeviceOwned(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  DeviceOwned(DeviceOwned&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  DeviceOwned& operator=(DeviceOwned&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  DeviceOwned(const DeviceOwned&) = delete;
  DeviceOwned& operator=(const DeviceOwned&) = delete;
  ~DeviceOwned() { reset(); }

  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

namespace vk {
using Buffer = DeviceOwned<VkBuffer, vkDestroyBuffer>;
using Memory = DeviceOwned<VkDeviceMemory, vkFreeMemory>;
using Image = DeviceOwned<VkImage, vkDestroyImage>;
using ImageView = DeviceOwned<VkImageView, vkDestroyImageView>;
using Sampler = DeviceOwned<VkSampler, vkDestroySampler>;
using ShaderModule = DeviceOwned<VkShaderModule, vkDestroyShaderModule>;
using Pipeline = DeviceOwned<VkPipeline, vkDestroyPipeline>;
using PipelineLayout = DeviceOwned<VkPipelineLayout, vkDestroyPipelineLayout>;
using PipelineCacheHandle = DeviceOwned<VkPipelineCache, vkDestroyPipelineCache>;
using DescriptorSetLayout = DeviceOwned<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = DeviceOwned<VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPool = DeviceOwned<VkCommandPool, vkDestroyCommandPool>;
using Fence = DeviceOwned<VkFence, vkDestroyFence>;
using Semaphore = DeviceOwned<VkSemaphore, vkDestroySemaphore>;
using Swapchain = DeviceOwned<VkSwapchainKHR, vkDestroySwapchainKHR>;
}  // namespace vk

}  // namespace mallet::render
