// The path tracer's one descriptor set: every binding of shaders/shared_types.h pointed at
// the render's resources (TLAS, frame constants, accumulation, scene buffers, textures).
#pragma once

#include <vulkan/vulkan.h>

#include "runtime/memo/material_cache.h"
#include "runtime/scene/gpu_textures.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// What the set points at; everything must outlive the set.
struct TraceResources {
  VkAccelerationStructureKHR tlas = VK_NULL_HANDLE;
  const GpuBuffer* frame = nullptr;         // gpu::FrameConstants
  const GpuBuffer* accumulation = nullptr;  // vec4 per pixel
  const GpuBuffer* rayCounter = nullptr;    // gpu::Counters
  const MaterialCache* cache = nullptr;     // entries, tile texels and log (dummies without)
  const SceneBuffers* scene = nullptr;
  const GpuTextures* textures = nullptr;
  const GpuBuffer* hitFeedback = nullptr;  // LiPaC's hit counters (a dummy without)
  // LiPaC's counting boxes; VK_NULL_HANDLE without (no shader then uses the binding).
  VkAccelerationStructureKHR countingBoxes = VK_NULL_HANDLE;
  // The wavefront path tracer's path state, queues and control (null for the megakernel,
  // whose layout has no such bindings).
  const GpuBuffer* pathState = nullptr;
  const GpuBuffer* pathQueues = nullptr;
  const GpuBuffer* wavefrontControl = nullptr;
};

class TraceDescriptorSet {
 public:
  TraceDescriptorSet(const VulkanContext& context, VkDescriptorSetLayout layout,
                     const TraceResources& resources);
  VkDescriptorSet get() const { return set_; }

 private:
  VulkanHandle<VkDescriptorPool> pool_;  // frees the set with it
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace memograph::runtime
