// The GPU instance fill (seeds/001 §3.3.2): the TLAS's instance records assembled on the GPU
// every frame from the instance states and the resident BLASes' addresses, instead of
// written by the host (CullingOptions::gpuInstanceFill, `--instance-fill gpu`). The host
// uploads a byte per instance and hitbox and an address per mesh; the records' templates
// (transforms, masks, counting boxes) are uploaded once. Same records, same order, as the
// host fill: instance_fill.comp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

class GpuInstanceFill {
 public:
  // `activeRecords`: each instance's record when active (its BLAS address is filled in per
  // frame from `meshOfInstance`); `boxRecords`: each instance's counting box, then each
  // hitbox's (empty without LiPaC: then no box is ever written); `meshCount` BLAS slots.
  // The compute shader's SPIR-V is cached in `shaderCacheDirectory` (none when empty), as
  // the renderer's are.
  GpuInstanceFill(const VulkanContext& context,
                  std::span<const VkAccelerationStructureInstanceKHR> activeRecords,
                  std::span<const std::uint32_t> meshOfInstance,
                  std::span<const VkAccelerationStructureInstanceKHR> boxRecords,
                  std::uint32_t hitboxCount, std::uint32_t meshCount,
                  const std::filesystem::path& shaderCacheDirectory);

  // Before the frame's submit: `states` one byte per instance (InstanceState) then one per
  // hitbox (1: it stands in the TLAS as a box); `meshAddresses` each mesh's BLAS, 0 when
  // not resident.
  void upload(std::span<const std::uint8_t> states, std::span<const VkDeviceAddress> meshAddresses);
  // Writes the instances' records at `records` and the counting boxes' at `boxRecords`
  // (device addresses; 0: no boxes), then a barrier that makes them visible to
  // acceleration-structure builds.
  void record(VkCommandBuffer commands, VkDeviceAddress records, VkDeviceAddress boxRecords) const;

 private:
  std::uint32_t instanceCount_ = 0;
  std::uint32_t hitboxCount_ = 0;
  std::uint32_t meshCount_ = 0;
  GpuBuffer activeRecords_;
  GpuBuffer boxRecords_;
  GpuBuffer meshOfInstance_;
  GpuBuffer states_;         // host-visible, per frame
  GpuBuffer meshAddresses_;  // host-visible, per frame
  PushConstantPass pass_;
};

}  // namespace memograph::runtime
