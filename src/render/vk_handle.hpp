#pragma once
// One RAII owner per kind of Vulkan object: a move-only handle that destroys its object
// with the right vkDestroy*/vkFree* call for its kind, on the device that made it.
// Device memory is counted besides (device_memory_bytes): a kiosk that runs for weeks must
// show that what it allocates comes back.
#include <atomic>
#include <cstdint>
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

namespace detail {
inline std::atomic<std::int64_t>& instances_and_devices_counter() {
  static std::atomic<std::int64_t> live{0};
  return live;
}
}  // namespace detail

//! Instances and devices this process holds through vk::Instance and vk::Device: a
//! constructor that failed half-way must leave it as it found it.
inline std::int64_t live_instances_and_devices() {
  return detail::instances_and_devices_counter().load(std::memory_order_relaxed);
}

//! The objects that are not made on a device (the instance, the device itself): owned the
//! same way, from the moment they exist, so that a constructor that fails half-way frees
//! what it made.
template <typename Handle, void (*Destroy)(Handle, const VkAllocationCallbacks*)>
class Owned {
 public:
  Owned() = default;
  explicit Owned(Handle handle) : handle_(handle) {
    if (handle_ != VK_NULL_HANDLE) detail::instances_and_devices_counter().fetch_add(1, std::memory_order_relaxed);
  }
  Owned(Owned&& other) noexcept : handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() { reset(); }

  void reset() {
    if (handle_ == VK_NULL_HANDLE) return;
    Destroy(handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
    detail::instances_and_devices_counter().fetch_sub(1, std::memory_order_relaxed);
  }
  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  Handle handle_ = VK_NULL_HANDLE;
};

namespace detail {
inline std::atomic<std::uint64_t>& device_memory_counter() {
  static std::atomic<std::uint64_t> bytes{0};
  return bytes;
}
}  // namespace detail

//! Bytes of device memory this process holds through vk::Memory (every vkAllocateMemory the
//! renderer makes, on any device); the swapchain's images, the driver's own, are not in it.
inline std::uint64_t device_memory_bytes() { return detail::device_memory_counter().load(std::memory_order_relaxed); }

namespace vk {
using Instance = Owned<VkInstance, vkDestroyInstance>;
using Device = Owned<VkDevice, vkDestroyDevice>;

//! The validation layer's messenger, destroyed through the instance's own entry point.
class DebugMessenger {
 public:
  DebugMessenger() = default;
  DebugMessenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger) : instance_(instance), handle_(messenger) {}
  DebugMessenger(DebugMessenger&& other) noexcept
      : instance_(other.instance_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  DebugMessenger& operator=(DebugMessenger&& other) noexcept {
    if (this != &other) {
      reset();
      instance_ = other.instance_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  DebugMessenger(const DebugMessenger&) = delete;
  DebugMessenger& operator=(const DebugMessenger&) = delete;
  ~DebugMessenger() { reset(); }
  void reset() {
    if (handle_ == VK_NULL_HANDLE) return;
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  VkDebugUtilsMessengerEXT get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT handle_ = VK_NULL_HANDLE;
};

using Buffer = DeviceOwned<VkBuffer, vkDestroyBuffer>;

//! A vkAllocateMemory result and its size, counted in device_memory_bytes() while held.
class Memory {
 public:
  Memory() = default;
  Memory(VkDevice device, VkDeviceMemory memory, VkDeviceSize size) : memory_(device, memory), size_(size) {
    detail::device_memory_counter().fetch_add(size_, std::memory_order_relaxed);
  }
  Memory(Memory&& other) noexcept : memory_(std::move(other.memory_)), size_(std::exchange(other.size_, 0)) {}
  Memory& operator=(Memory&& other) noexcept {
    if (this != &other) {
      reset();
      memory_ = std::move(other.memory_);
      size_ = std::exchange(other.size_, 0);
    }
    return *this;
  }
  Memory(const Memory&) = delete;
  Memory& operator=(const Memory&) = delete;
  ~Memory() { reset(); }
  void reset() {
    if (memory_) detail::device_memory_counter().fetch_sub(size_, std::memory_order_relaxed);
    memory_.reset();
    size_ = 0;
  }
  VkDeviceMemory get() const { return memory_.get(); }
  explicit operator bool() const { return static_cast<bool>(memory_); }
  VkDeviceSize size() const { return size_; }

 private:
  DeviceOwned<VkDeviceMemory, vkFreeMemory> memory_;
  VkDeviceSize size_ = 0;
};

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
