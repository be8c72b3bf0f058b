// The material textures on the device: one mipmapped RGBA32F image per texture slot and one
// trilinear, repeating sampler, bound as the path tracer's array of sampled images
// (mg_SampleTexture picks the level from the ray-cone gradients with textureGrad).
#pragma once

#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/host/image.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

class GpuTextures {
 public:
  // With no textures, one 1x1 white texture is made so the array binding is never empty.
  GpuTextures(const VulkanContext& context, const std::vector<TextureImage>& textures);

  std::uint32_t count() const { return static_cast<std::uint32_t>(views_.size()); }
  VkImageView view(std::uint32_t index) const { return views_[index].get(); }
  VkSampler sampler() const { return sampler_.get(); }
  std::uint64_t bytes() const { return bytes_; }

 private:
  std::vector<VulkanHandle<VkDeviceMemory>> memories_;
  std::vector<VulkanHandle<VkImage>> images_;
  std::vector<VulkanHandle<VkImageView>> views_;
  VulkanHandle<VkSampler> sampler_;
  std::uint64_t bytes_ = 0;
};

}  // namespace memograph::runtime
