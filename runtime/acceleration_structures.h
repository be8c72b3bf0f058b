// Acceleration structures of a scene: one BLAS per mesh, shared by all of its instances and
// compacted after the build (every mesh is static), and one TLAS over the instances. Their
// memory (BLAS, TLAS, scratch) is reported, since a later issue culls it.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>
#include <glm/glm.hpp>

#include "runtime/gpu_buffer.h"
#include "runtime/vulkan_context.h"
#include "runtime/vulkan_handle.h"

namespace memograph::runtime {

struct AccelerationStructureStats {
  std::uint32_t blasCount = 0;
  std::uint32_t instanceCount = 0;
  std::uint64_t blasBytes = 0;  // after compaction
  std::uint64_t blasBytesBeforeCompaction = 0;
  std::uint64_t tlasBytes = 0;
  std::uint64_t scratchBytes = 0;  // build scratch allocated (freed after the build)
  double buildMilliseconds = 0.0;  // wall time of all builds, compaction included
};

// Where one mesh lies in the shared vertex and index buffers.
struct MeshGeometry {
  std::uint32_t firstVertex = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t firstIndex = 0;
  std::uint32_t triangleCount = 0;
};

struct InstancePlacement {
  std::uint32_t mesh = 0;
  glm::mat4 objectToWorld{1.0f};
  // false: a light's quad (Blender area lights): TLAS mask 0x01, which shadow and camera rays
  // (cull mask 0xFE) skip and only BSDF rays find, as Cycles' lamps.
  bool castsShadow = true;
};

class AccelerationStructure {
 public:
  AccelerationStructure() = default;
  AccelerationStructure(const VulkanContext& context, VkAccelerationStructureTypeKHR type,
                        VkDeviceSize size);
  VkAccelerationStructureKHR handle() const { return handle_.get(); }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize size() const { return buffer_.size(); }

 private:
  GpuBuffer buffer_;
  VulkanHandle<VkAccelerationStructureKHR> handle_;
  VkDeviceAddress address_ = 0;
};

class SceneAccelerationStructures {
 public:
  // `vertices` holds gpu::Vertex records (position first), `indices` uint32 triangles with
  // indices relative to each mesh's first vertex.
  SceneAccelerationStructures(const VulkanContext& context, const GpuBuffer& vertices,
                              std::uint32_t vertexStride, const GpuBuffer& indices,
                              const std::vector<MeshGeometry>& meshes,
                              const std::vector<InstancePlacement>& instances);

  VkAccelerationStructureKHR tlas() const { return tlas_.handle(); }
  const AccelerationStructureStats& stats() const { return stats_; }

 private:
  std::vector<AccelerationStructure> blases_;
  AccelerationStructure tlas_;
  AccelerationStructureStats stats_;
};

}  // namespace memograph::runtime
