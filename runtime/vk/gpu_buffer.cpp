#include "runtime/vk/gpu_buffer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

void checkBufferSize(const VulkanContext& context, std::uint64_t bytes, const std::string& what,
                     bool storageBinding) {
  const DeviceInfo& info = context.info();
  if (info.maxMemoryAllocationSize > 0 && bytes > info.maxMemoryAllocationSize)
    throw std::invalid_argument(what + " needs " + std::to_string(bytes) +
                                " bytes in one buffer, more than the largest allocation of " +
                                info.name + " (" + std::to_string(info.maxMemoryAllocationSize) +
                                " bytes)");
  const std::uint64_t range = info.limits.maxStorageBufferRange;
  if (storageBinding && range > 0 && bytes > range)
    throw std::invalid_argument(what + " needs " + std::to_string(bytes) +
                                " bytes in one storage buffer, more than the " +
                                std::to_string(range) + "-byte storage-buffer range of " +
                                info.name + " (the most one binding may address)");
}

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
  checkBufferSize(context, requirements.size, "a GPU buffer", false);
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
