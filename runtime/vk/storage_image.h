// A device-local storage image for shaders' imageLoad/imageStore, in the GENERAL layout and
// with undefined contents: the tile cache's texel storage (--tile-storage texture2d|
// texture3d, thesis §5.4.1) and the cache self-test's image modes.
#pragma once

#include <vulkan/vulkan.h>

#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

struct StorageImage {
  // Destroyed in reverse order: the view, then the image, then its memory.
  VulkanHandle<VkDeviceMemory> memory;
  VulkanHandle<VkImage> image;
  VulkanHandle<VkImageView> view;
  VkDeviceSize bytes = 0;  // the memory bound to it
};

// Device-local memory allocated for `image` and bound to it; `bytes` is its size. `what`
// names the image in error messages. Throws std::runtime_error on a Vulkan error.
struct ImageMemory {
  VulkanHandle<VkDeviceMemory> memory;
  VkDeviceSize bytes = 0;
};
ImageMemory bindDeviceLocalImageMemory(const VulkanContext& context, VkImage image,
                                       const char* what);

// One mip level and layer of `format` (2D or 3D as `type`), transitioned to GENERAL before
// it returns. `what` names it in error messages. Throws std::runtime_error on a Vulkan error.
StorageImage createStorageImage(const VulkanContext& context, VkImageType type, VkFormat format,
                                VkExtent3D extent, const char* what);

}  // namespace memograph::runtime
