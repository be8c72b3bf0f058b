#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

const char* resultName(VkResult result) {
  switch (result) {
#define MG_RESULT(name) \
  case name:            \
    return #name;
    MG_RESULT(VK_SUCCESS)
    MG_RESULT(VK_NOT_READY)
    MG_RESULT(VK_TIMEOUT)
    MG_RESULT(VK_INCOMPLETE)
    MG_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    MG_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    MG_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    MG_RESULT(VK_ERROR_DEVICE_LOST)
    MG_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    MG_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    MG_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    MG_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    MG_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    MG_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    MG_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    MG_RESULT(VK_ERROR_FRAGMENTED_POOL)
    MG_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    MG_RESULT(VK_ERROR_INVALID_SHADER_NV)
    MG_RESULT(VK_OPERATION_DEFERRED_KHR)
    MG_RESULT(VK_OPERATION_NOT_DEFERRED_KHR)
#undef MG_RESULT
    default:
      return "VkResult(unknown)";
  }
}

void checkVk(VkResult result, const char* call) {
  if (result >= 0)
    return;
  std::string message = std::string(call) + " failed: " + resultName(result) + " (" +
                        std::to_string(static_cast<int>(result)) + ")";
  switch (result) {
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      message += ". The GPU ran out of memory: render a smaller image or a smaller scene.";
      break;
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      message += ". The host ran out of memory.";
      break;
    case VK_ERROR_DEVICE_LOST:
      message +=
          ". The device was lost (a driver reset or a shader that ran too long); try fewer "
          "paths per frame or a smaller image.";
      break;
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      message += ". No Vulkan driver supports the API version asked for (1.2).";
      break;
    default:
      break;
  }
  throw VulkanError(message, result);
}

}  // namespace memograph::runtime
