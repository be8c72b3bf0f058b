// Device buffers with their own memory: device-local ones filled through a staging copy,
// host-visible ones mapped for uploads and read-backs, all with device addresses when the
// usage asks for them (acceleration-structure inputs, scratch, shader-binding tables).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>
#include <glm/glm.hpp>

#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// `value` rounded up to a multiple of `alignment` (offsets and addresses of scratch slices,
// shader-binding-table records).
inline VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

// A device address as the (low, high) uint pair that push constants carry it in, for
// GL_EXT_buffer_reference_uvec2 (shaders cast the pair to a buffer reference).
inline glm::uvec2 addressWords(VkDeviceAddress address) {
  return {static_cast<std::uint32_t>(address), static_cast<std::uint32_t>(address >> 32)};
}

class GpuBuffer {
 public:
  GpuBuffer() = default;
  GpuBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
            VkMemoryPropertyFlags memory);

  VkBuffer buffer() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  void* mapped() const { return mapped_; }  // null unless host-visible

  // Copies bytes in (host-visible buffers only).
  void write(const void* data, std::size_t bytes, std::size_t offset = 0);
  void read(void* data, std::size_t bytes, std::size_t offset = 0) const;

 private:
  VulkanHandle<VkDeviceMemory> memory_;
  VulkanHandle<VkBuffer> buffer_;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;
};

// Refuses (std::invalid_argument) a buffer of `bytes` the device cannot hold in one
// allocation (past it vkAllocateMemory may fail or, on lavapipe, crash) or, when it is bound
// whole as a storage buffer, address in one binding (maxStorageBufferRange: binding more is
// invalid usage, which lavapipe does not catch). `what` names the buffer in the message,
// e.g. the option that sized it.
void checkBufferSize(const VulkanContext& context, std::uint64_t bytes, const std::string& what,
                     bool storageBinding);

// A device-local buffer holding `bytes` (at least 16 bytes, so empty arrays still bind).
GpuBuffer uploadBuffer(const VulkanContext& context, const void* data, std::size_t bytes,
                       VkBufferUsageFlags usage);

template <typename T>
GpuBuffer uploadBuffer(const VulkanContext& context, std::span<const T> items,
                       VkBufferUsageFlags usage) {
  return uploadBuffer(context, items.data(), items.size_bytes(), usage);
}

// A host-visible, coherent buffer (uniforms, read-backs).
GpuBuffer hostBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage);

}  // namespace memograph::runtime
