// Errors from the Vulkan layer as exceptions with messages for people: the failing call,
// the VkResult by name, and for out-of-memory and device-lost what to try next.
#pragma once

#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace memograph::runtime {

class VulkanError : public std::runtime_error {
 public:
  VulkanError(std::string what, VkResult result)
      : std::runtime_error(std::move(what)), result_(result) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

const char* resultName(VkResult result);

// Throws VulkanError naming `call` unless `result` is VK_SUCCESS (or another non-error code).
void checkVk(VkResult result, const char* call);

}  // namespace memograph::runtime
