#pragma once
// Vulkan failures as exceptions that say what was being done and what the driver said.
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace mallet::render {

//! The renderer cannot go on (no Vulkan 1.3 device, device lost, out of memory …).
//! `result` is the VkResult that caused it (VK_SUCCESS when it is not a Vulkan call).
class RenderError : public std::runtime_error {
 public:
  RenderError(const std::string& what, VkResult result = VK_SUCCESS)
      : std::runtime_error(what), result_(result) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

const char* result_name(VkResult result);

//! Throws RenderError("doing: VK_ERROR_…") unless `result` is VK_SUCCESS.
inline void check(VkResult result, const char* doing) {
  if (result != VK_SUCCESS) throw RenderError(std::string(doing) + ": " + result_name(result), result);
}

}  // namespace mallet::render
