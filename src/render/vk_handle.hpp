#pragma once
// One RAII owner for every kind of Vulkan object (Unique): a move-only handle that destroys
// its object with the right vkDestroy*/vkFree* call for its kind, on what made it.
// Device memory is counted besides (device_memory_bytes): a kiosk that runs for weeks must
// show that what it allocates comes back.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include <vulkan/vulkan.h>

namespace mallet::render {

namespace detail {
inline std::atomic<std::int64_t>& instances_and_devices_counter() {
  static std::atomic<std::int64_t> live{0};
  return live;
}
inline std::atomic<std::uint64_t>& device_memory_counter() {
  static std::atomic<std::uint64_t> bytes{0};
  return bytes;
}

//! What an owner counts while it holds its object: nothing; one instance or device; the
//! bytes of one allocation.
struct Uncounted {
  void acquired() const {}
  void released() const {}
};
struct InstanceOrDevice {
  void acquired() const { instances_and_devices_counter().fetch_add(1, std::memory_order_relaxed); }
  void released() const { instances_and_devices_counter().fetch_sub(1, std::memory_order_relaxed); }
};
struct MemoryBytes {
  VkDeviceSize size = 0;
  void acquired() const { device_memory_counter().fetch_add(size, std::memory_order_relaxed); }
  void released() const { device_memory_counter().fetch_sub(size, std::memory_order_relaxed); }
};

//! The validation layer's messenger is destroyed through the instance's own entry point.
inline void destroy_debug_messenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger,
                                    const VkAllocationCallbacks* allocator) {
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  if (destroy) destroy(instance, messenger, allocator);
}
}  // namespace detail

//! Instances and devices this process holds through vk::Instance and vk::Device: a
//! constructor that failed half-way must leave it as it found it.
inline std::int64_t live_instances_and_devices() {
  return detail::instances_and_devices_counter().load(std::memory_order_relaxed);
}

//! Bytes of device memory this process holds through vk::Memory (every vkAllocateMemory the
//! renderer makes, on any device); the swapchain's images, the driver's own, are not in it.
inline std::uint64_t device_memory_bytes() { return detail::device_memory_counter().load(std::memory_order_relaxed); }

//! The one owner of a Vulkan object: move-only, it frees the object with `Destroy` from the
//! moment it exists. `Parent` is what made it (a device, an instance), or std::nullptr_t for
//! the instance and the device themselves; `Count` is what it counts while it holds it.
template <typename Parent, typename Handle, auto Destroy, typename Count = detail::Uncounted>
class Unique {
 public:
  Unique() = default;
  Unique(Parent parent, Handle handle, Count count = {}) : parent_(parent), handle_(handle), count_(count) {
    if (handle_ != VK_NULL_HANDLE) count_.acquired();
  }
  explicit Unique(Handle handle)
    requires std::is_same_v<Parent, std::nullptr_t>
      : Unique(nullptr, handle) {}
  Unique(Unique&& other) noexcept
      : parent_(other.parent_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)),
        count_(std::exchange(other.count_, Count{})) {}
  Unique& operator=(Unique&& other) noexcept {
    if (this != &other) {
      reset();
      parent_ = other.parent_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
      count_ = std::exchange(other.count_, Count{});
    }
    return *this;
  }
  Unique(const Unique&) = delete;
  Unique& operator=(const Unique&) = delete;
  ~Unique() { reset(); }

  void reset() {
    if (handle_ == VK_NULL_HANDLE) return;
    if constexpr (std::is_same_v<Parent, std::nullptr_t>) Destroy(handle_, nullptr);
    else Destroy(parent_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
    count_.released();
    count_ = Count{};
  }
  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  Parent parent_{};
  Handle handle_ = VK_NULL_HANDLE;
  [[no_unique_address]] Count count_;
};

//! An object made on a device, destroyed by its vkDestroy* on that device.
template <typename Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
using DeviceOwned = Unique<VkDevice, Handle, Destroy>;

namespace vk {
using Instance = Unique<std::nullptr_t, VkInstance, vkDestroyInstance, detail::InstanceOrDevice>;
using Device = Unique<std::nullptr_t, VkDevice, vkDestroyDevice, detail::InstanceOrDevice>;
using DebugMessenger = Unique<VkInstance, VkDebugUtilsMessengerEXT, detail::destroy_debug_messenger>;
using Buffer = DeviceOwned<VkBuffer, vkDestroyBuffer>;
//! A vkAllocateMemory result, its size counted in device_memory_bytes() while held.
using Memory = Unique<VkDevice, VkDeviceMemory, vkFreeMemory, detail::MemoryBytes>;
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
