#include "runtime/vk/storage_image.h"

#include <string>

#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

ImageMemory bindDeviceLocalImageMemory(const VulkanContext& context, VkImage image,
                                       const char* what) {
  const VkDevice device = context.device();
  const std::string name(what);
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(device, image, &requirements);
  VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex =
      context.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  checkVk(vkAllocateMemory(device, &allocate, nullptr, &memory),
          ("vkAllocateMemory (" + name + ")").c_str());
  ImageMemory out;
  out.memory = VulkanHandle<VkDeviceMemory>(
      memory, [device](VkDeviceMemory m) { vkFreeMemory(device, m, nullptr); });
  checkVk(vkBindImageMemory(device, image, memory, 0),
          ("vkBindImageMemory (" + name + ")").c_str());
  out.bytes = requirements.size;
  return out;
}

StorageImage createStorageImage(const VulkanContext& context, VkImageType type, VkFormat format,
                                VkExtent3D extent, const char* what) {
  const VkDevice device = context.device();
  const std::string name(what);
  StorageImage out;

  VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  imageInfo.imageType = type;
  imageInfo.format = format;
  imageInfo.extent = extent;
  imageInfo.mipLevels = 1;
  imageInfo.arrayLayers = 1;
  imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
  imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
  imageInfo.usage = VK_IMAGE_USAGE_STORAGE_BIT;
  imageInfo.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  checkVk(vkCreateImage(device, &imageInfo, nullptr, &image),
          ("vkCreateImage (" + name + ")").c_str());
  out.image =
      VulkanHandle<VkImage>(image, [device](VkImage i) { vkDestroyImage(device, i, nullptr); });

  ImageMemory memory = bindDeviceLocalImageMemory(context, image, what);
  out.memory = std::move(memory.memory);
  out.bytes = memory.bytes;

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image;
  viewInfo.viewType = type == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = format;
  viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  checkVk(vkCreateImageView(device, &viewInfo, nullptr, &view),
          ("vkCreateImageView (" + name + ")").c_str());
  out.view = VulkanHandle<VkImageView>(
      view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });

  // GENERAL for the shaders' loads and stores. The contents need no clear: a texel is only
  // read under a key that was published after it was written.
  context.submitAndWait([&](VkCommandBuffer commands) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr, 1,
                         &barrier);
  });
  return out;
}

}  // namespace memograph::runtime
