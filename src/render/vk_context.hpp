#pragma once
// The Vulkan 1.3 instance, the chosen physical device, its logical device with dynamic
// rendering and synchronization2, one graphics queue and a command pool. Validation
// layers are enabled on request; every message they send is counted (tests assert the
// count is zero) and printed once to stderr.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "render/vk_handle.hpp"

namespace mallet::render {

enum class Validation {
  off,
  if_available,  //!< Debug builds: on when Debian's vulkan-validationlayers is installed
  required,      //!< tests: a missing layer is an error, never a silent pass
};

struct ContextOptions {
  Validation validation = Validation::off;
  std::vector<std::string> instance_extensions;  //!< e.g. what GLFW needs for a surface
  bool swapchain = false;                        //!< enable VK_KHR_swapchain on the device
  std::string device_name;                       //!< substring of the device to use; empty = best
  //! Tests only: throw RenderError right after this step ("instance", "messenger",
  //! "device" or "command pool"), to check that what was made by then is freed.
  std::string fail_after;
};

class Context {
 public:
  explicit Context(const ContextOptions& options);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  VkCommandPool command_pool() const { return pool_.get(); }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string device_name() const { return properties_.deviceName; }
  bool validation_enabled() const { return static_cast<bool>(messenger_); }

  //! Messages the validation layers sent (warnings and errors) since creation.
  std::uint64_t validation_messages() const { return validation_messages_.load(); }
  std::string first_validation_message() const;

  //! A memory type index with `required` bits among `type_bits`; throws if none.
  std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const;

  //! A primary command buffer from the context's pool (the caller frees it with
  //! free_command_buffer), a fence (optionally signalled) and a binary semaphore.
  VkCommandBuffer allocate_command_buffer() const;
  void free_command_buffer(VkCommandBuffer cmd) const;
  vk::Fence make_fence(bool signaled = false) const;
  vk::Semaphore make_semaphore() const;

  //! Records `record` into a fresh command buffer, submits it and waits for it.
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

  //! Called by the debug messenger.
  void on_validation_message(const char* message);

 private:
  // The validation layer reports to these until the instance is gone: they come first, so
  // they are destroyed last.
  std::atomic<std::uint64_t> validation_messages_{0};
  mutable std::mutex message_mutex_;
  std::string first_message_;
  // Each Vulkan object owned from the moment it exists, and destroyed in reverse order (the
  // pool, the device, the messenger, the instance), on a failed constructor too.
  vk::Instance instance_;
  vk::DebugMessenger messenger_;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  vk::Device device_;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  vk::CommandPool pool_;
};

}  // namespace mallet::render
