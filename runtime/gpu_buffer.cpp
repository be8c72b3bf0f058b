#include "runtime/gpu_buffer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "runtime/vulkan_error.h"

namespace memograph::runtime {

GpuBuffer::GpuBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
                     VkMemoryPropertyFlags memory)
    : size_(size) {
  VkDevice device = context.device();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = std::max<VkDeviceSize>(size, 16);
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  checkVk(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
  buffer_ =
      VulkanHandle<VkBuffer>(buffer, [device](VkBuffer b) { vkDestroyBuffer(device, b, nullptr); });

  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, buffer, &requirements);
  // Past the device's largest allocation vkAllocateMemory may fail or (lavapipe) crash.
  const VkDeviceSize largest = context.info().maxMemoryAllocationSize;
  if (largest > 0 && requirements.size > largest)
    throw std::runtime_error("a GPU buffer of " + std::to_string(requirements.size) +
                             " bytes is larger than the largest single allocation of " +
                             context.info().name + " (" + std::to_string(largest) + " bytes)");
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  bool wantsAddress = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
  allocate.pNext = wantsAddress ? &flags : nullptr;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = context.findMemoryType(requirements.memoryTypeBits, memory);
  VkDeviceMemory deviceMemory = VK_NULL_HANDLE;
  checkVk(vkAllocateMemory(device, &allocate, nullptr, &deviceMemory), "vkAllocateMemory");
  memory_ = VulkanHandle<VkDeviceMemory>(
      deviceMemory, [device](VkDeviceMemory m) { vkFreeMemory(device, m, nullptr); });
  checkVk(vkBindBufferMemory(device, buffer, deviceMemory, 0), "vkBindBufferMemory");
  if (memory & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    checkVk(vkMapMemory(device, deviceMemory, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  }
  if (wantsAddress) {
    VkBufferDeviceAddressInfo addressInfo{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addressInfo.buffer = buffer;
    address_ = vkGetBufferDeviceAddress(device, &addressInfo);
  }
}

void GpuBuffer::write(const void* data, std::size_t bytes, std::size_t offset) {
  if (!mapped_)
    throw std::logic_error("GpuBuffer::write on a buffer that is not host-visible");
  if (bytes)
    std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
}

void GpuBuffer::read(void* data, std::size_t bytes, std::size_t offset) const {
  if (!mapped_)
    throw std::logic_error("GpuBuffer::read on a buffer that is not host-visible");
  if (bytes)
    std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
}

GpuBuffer uploadBuffer(const VulkanContext& context, const void* data, std::size_t bytes,
                       VkBufferUsageFlags usage) {
  VkDeviceSize size = std::max<std::size_t>(bytes, 16);
  GpuBuffer target(context, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (bytes == 0)
    return target;
  GpuBuffer staging = hostBuffer(context, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  staging.write(data, bytes);
  context.submitAndWait([&](VkCommandBuffer commands) {
    VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(commands, staging.buffer(), target.buffer(), 1, &copy);
  });
  return target;
}

GpuBuffer hostBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage) {
  return GpuBuffer(context, size, usage,
                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
}

}  // namespace memograph::runtime
