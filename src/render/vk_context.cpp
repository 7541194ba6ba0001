#include "render/vk_context.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/journal.hpp"
#include "render/vk_error.hpp"

namespace mallet::render {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                VkDebugUtilsMessageTypeFlagsEXT,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                void* user) {
  static_cast<Context*>(user)->on_validation_message(data && data->pMessage ? data->pMessage : "(no text)");
  return VK_FALSE;
}

bool layer_available(const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

int device_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

}  // namespace

Context::Context(const ContextOptions& options) {
  bool validate = false;
  if (options.validation != Validation::off) {
    validate = layer_available(kValidationLayer);
    if (!validate && options.validation == Validation::required)
      throw RenderError(std::string("Vulkan validation layer ") + kValidationLayer +
                        " is not installed (Debian package vulkan-validationlayers)");
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "mallet";
  app.apiVersion = VK_API_VERSION_1_3;
  std::vector<const char*> extensions;
  for (const std::string& e : options.instance_extensions) extensions.push_back(e.c_str());
  if (validate) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = on_debug_message;
  messenger.pUserData = this;

  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  if (validate) {
    ici.enabledLayerCount = 1;
    ici.ppEnabledLayerNames = &kValidationLayer;
    ici.pNext = &messenger;  // also covers instance creation and destruction
  }
  auto injected = [&](const char* step) {
    if (options.fail_after == step) throw RenderError(std::string("injected failure after the ") + step);
  };
  VkInstance instance = VK_NULL_HANDLE;
  check(vkCreateInstance(&ici, nullptr, &instance),
        "creating the Vulkan instance (is a Vulkan driver installed? Debian: mesa-vulkan-drivers)");
  instance_ = vk::Instance(instance);
  injected("instance");
  if (validate) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerEXT made = VK_NULL_HANDLE;
    if (create && create(instance, &messenger, nullptr, &made) == VK_SUCCESS)
      messenger_ = vk::DebugMessenger(instance, made);
  }
  injected("messenger");

  // The device: the named one, else the best kind that has Vulkan 1.3 and a graphics queue.
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  int best_rank = -1;
  std::string seen;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    seen += (seen.empty() ? "" : ", ") + std::string(p.deviceName);
    if (p.apiVersion < VK_API_VERSION_1_3) continue;
    if (!options.device_name.empty() && std::string(p.deviceName).find(options.device_name) == std::string::npos)
      continue;
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &families, props.data());
    for (std::uint32_t f = 0; f < families; ++f) {
      if (!(props[f].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
      if (device_rank(p.deviceType) > best_rank) {
        best_rank = device_rank(p.deviceType);
        physical_ = d;
        properties_ = p;
        queue_family_ = f;
      }
      break;
    }
  }
  if (physical_ == VK_NULL_HANDLE) {  // the messenger and the instance go with the throw
    std::string want = options.device_name.empty() ? "" : " named '" + options.device_name + "'";
    throw RenderError("no Vulkan 1.3 device" + want + " with a graphics queue (seen: " +
                      (seen.empty() ? "none" : seen) + ")");
  }
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  v13.dynamicRendering = VK_TRUE;
  v13.synchronization2 = VK_TRUE;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queue_family_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  const char* swapchain_ext = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &v13;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  if (options.swapchain) {
    dci.enabledExtensionCount = 1;
    dci.ppEnabledExtensionNames = &swapchain_ext;
  }
  VkDevice device = VK_NULL_HANDLE;
  check(vkCreateDevice(physical_, &dci, nullptr, &device), "creating the Vulkan device");
  device_ = vk::Device(device);
  vkGetDeviceQueue(device, queue_family_, 0, &queue_);
  injected("device");

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queue_family_;
  VkCommandPool pool;
  check(vkCreateCommandPool(device, &pci, nullptr, &pool), "creating a command pool");
  pool_ = vk::CommandPool(device, pool);
  injected("command pool");
}

Context::~Context() {
  if (device_) vkDeviceWaitIdle(device_.get());
  // The members go in reverse order: the pool, the device, the messenger, the instance.
}

void Context::on_validation_message(const char* message) {
  if (validation_messages_.fetch_add(1) == 0) {
    std::lock_guard lock(message_mutex_);
    first_message_ = message;
  }
  journal::warning("vulkan validation: {}", message);
}

std::string Context::first_validation_message() const {
  std::lock_guard lock(message_mutex_);
  return first_message_;
}

std::uint32_t Context::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
  throw RenderError("no Vulkan memory type with the needed properties");
}

VkCommandBuffer Context::allocate_command_buffer() const {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_.get();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  check(vkAllocateCommandBuffers(device_.get(), &ai, &cmd), "allocating a command buffer");
  return cmd;
}

void Context::free_command_buffer(VkCommandBuffer cmd) const {
  vkFreeCommandBuffers(device_.get(), pool_.get(), 1, &cmd);
}

vk::Fence Context::make_fence(bool signaled) const {
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (signaled) fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkFence fence;
  check(vkCreateFence(device_.get(), &fci, nullptr, &fence), "creating a fence");
  return vk::Fence(device_.get(), fence);
}

vk::Semaphore Context::make_semaphore() const {
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore s;
  check(vkCreateSemaphore(device_.get(), &sci, nullptr, &s), "creating a semaphore");
  return vk::Semaphore(device_.get(), s);
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
  const VkCommandBuffer cmd = allocate_command_buffer();
  struct Free {
    const Context& ctx;
    VkCommandBuffer c;
    ~Free() { ctx.free_command_buffer(c); }
  } free_later{*this, cmd};
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "beginning a command buffer");
  record(cmd);
  check(vkEndCommandBuffer(cmd), "ending a command buffer");
  const vk::Fence fence = make_fence();
  VkFence raw_fence = fence.get();
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  check(vkQueueSubmit2(queue_, 1, &si, fence.get()), "submitting to the GPU queue");
  check(vkWaitForFences(device_.get(), 1, &raw_fence, VK_TRUE, UINT64_MAX), "waiting for the GPU");
}

const char* result_name(VkResult r) {
  switch (r) {
#define MALLET_RESULT(x) \
  case x: return #x;
    MALLET_RESULT(VK_SUCCESS)
    MALLET_RESULT(VK_NOT_READY)
    MALLET_RESULT(VK_TIMEOUT)
    MALLET_RESULT(VK_INCOMPLETE)
    MALLET_RESULT(VK_SUBOPTIMAL_KHR)
    MALLET_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    MALLET_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    MALLET_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    MALLET_RESULT(VK_ERROR_DEVICE_LOST)
    MALLET_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    MALLET_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    MALLET_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    MALLET_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    MALLET_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    MALLET_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    MALLET_RESULT(VK_ERROR_SURFACE_LOST_KHR)
    MALLET_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    MALLET_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
#undef MALLET_RESULT
    default: return "VkResult (other)";
  }
}

}  // namespace mallet::render
