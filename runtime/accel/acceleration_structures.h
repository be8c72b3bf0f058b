// Acceleration structures: batched, compacted BLAS builds, a TLAS rebuilt from host-written
// instance records, and a scene's static set of them (one BLAS per mesh, shared by all of
// its instances, and one TLAS over every instance) for renders without culling (culled
// renders: blas_cache.h, scene_culling.h). Their memory (BLAS, TLAS, scratch) is reported.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>
#include <glm/glm.hpp>

#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// Usage of buffers that acceleration-structure builds read (vertices, indices, instance
// records).
inline constexpr VkBufferUsageFlags kAccelerationBuildInput =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
    VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

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

// A mesh's opaque triangles in the shared buffers (`vertices`: records of `vertexStride`
// bytes, position first; `indices`: uint32 relative to the mesh's first vertex).
VkAccelerationStructureGeometryKHR meshGeometry(const GpuBuffer& vertices,
                                                std::uint32_t vertexStride,
                                                const GpuBuffer& indices, const MeshGeometry& mesh);

// The build of one structure of `type` from one geometry (scratch and destination are
// the caller's).
VkAccelerationStructureBuildGeometryInfoKHR buildGeometryInfo(
    VkAccelerationStructureTypeKHR type, VkBuildAccelerationStructureFlagsKHR flags,
    VkBuildAccelerationStructureModeKHR mode, const VkAccelerationStructureGeometryKHR* geometry);

// One batch of BLAS builds: one scratch buffer with a slice per build, one submit, then
// each BLAS copied into a structure of its compacted size (§3.3.1: batching, compaction).
struct CompactedBlases {
  std::vector<AccelerationStructure> blases;  // one per mesh given, in order
  std::uint64_t bytes = 0;                    // after compaction
  std::uint64_t bytesBeforeCompaction = 0;
  std::uint64_t scratchBytes = 0;
  std::uint64_t triangles = 0;
  double gpuMilliseconds = 0.0;  // the builds alone, from timestamps (0 without them)
};
// `vertices` holds records of `vertexStride` bytes, position first; `indices` uint32
// triangles relative to each mesh's first vertex. Throws on a mesh without triangles.
CompactedBlases buildCompactedBlases(const VulkanContext& context, const GpuBuffer& vertices,
                                     std::uint32_t vertexStride, const GpuBuffer& indices,
                                     std::span<const MeshGeometry> meshes);

// A TLAS instance record: row-major 3x4 transform, custom index (the shaders' instance or
// counter slot), cull mask, hit group 0, no facing culling.
VkAccelerationStructureInstanceKHR instanceRecord(const glm::mat4& objectToWorld,
                                                  std::uint32_t customIndex, std::uint32_t mask,
                                                  VkDeviceAddress blas);

// A TLAS rebuilt from instance records the host writes into mapped memory, sized once for
// `capacity` records so that its handle (and the descriptor set that names it) never
// changes. The build reads the records on the device: write them only while no build of
// this structure is in flight.
class TopLevelStructure {
 public:
  TopLevelStructure(const VulkanContext& context, std::uint32_t capacity);
  VkAccelerationStructureInstanceKHR* records() const;
  std::uint32_t capacity() const { return capacity_; }
  // Records the build of the first `count` records and a barrier that makes it visible to
  // the ray-tracing and compute shaders after it.
  void recordBuild(VkCommandBuffer commands, std::uint32_t count) const;
  VkAccelerationStructureKHR handle() const { return tlas_.handle(); }
  std::uint64_t bytes() const { return tlas_.size(); }
  std::uint64_t scratchBytes() const { return scratch_.size(); }
  std::uint64_t instanceBufferBytes() const { return instances_.size(); }

 private:
  const VulkanContext* context_ = nullptr;
  std::uint32_t capacity_ = 0;
  GpuBuffer instances_;
  GpuBuffer scratch_;
  AccelerationStructure tlas_;
};

class SceneAccelerationStructures {
 public:
  // `vertices` holds gpu::Vertex records (position first), `indices` uint32 triangles with
  // indices relative to each mesh's first vertex.
  SceneAccelerationStructures(const VulkanContext& context, const GpuBuffer& vertices,
                              std::uint32_t vertexStride, const GpuBuffer& indices,
                              const std::vector<MeshGeometry>& meshes,
                              const std::vector<InstancePlacement>& instances);

  VkAccelerationStructureKHR tlas() const { return tlas_->handle(); }
  const AccelerationStructureStats& stats() const { return stats_; }
  // The TLAS's build scratch, which it keeps (the BLASes' is freed after their build).
  std::uint64_t residentScratchBytes() const { return tlas_->scratchBytes(); }

 private:
  std::vector<AccelerationStructure> blases_;
  std::unique_ptr<TopLevelStructure> tlas_;
  AccelerationStructureStats stats_;
};

}  // namespace memograph::runtime
