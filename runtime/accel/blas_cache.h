// BLAS residency for culled renders (seeds/001 §3.3.1): one shared, compacted BLAS per mesh,
// built when an instance in the TLAS first needs it, in batches up to a triangle budget and
// a time budget per frame, and evicted when no instance in the TLAS has used it for `keepFrames`
// frames, or, least recently used first, once the resident BLASes pass a memory budget.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "runtime/accel/acceleration_structures.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

struct BlasFrameWork {
  std::uint32_t builds = 0;
  std::uint32_t evictions = 0;
  std::uint64_t trianglesBuilt = 0;
  std::uint32_t waiting = 0;       // needed meshes left for later frames by the build budgets
  std::uint64_t scratchBytes = 0;  // this frame's largest batch's scratch (freed after it)
  double gpuMilliseconds = 0.0;    // the builds, from timestamps
};

class BlasCache {
 public:
  // budgetBytes, buildTriangles, buildMilliseconds (GPU time of a frame's builds, at the rate
  // measured by the builds' timestamps so far), keepFrames: 0 for no limit. The buffers must
  // outlive the cache.
  BlasCache(const VulkanContext& context, const GpuBuffer& vertices, std::uint32_t vertexStride,
            const GpuBuffer& indices, std::vector<MeshGeometry> meshes, std::uint64_t budgetBytes,
            std::uint64_t buildTriangles, double buildMilliseconds, std::uint32_t keepFrames);

  // The meshes the frame's TLAS needs (repeats allowed): builds the missing ones, lowest mesh
  // index first, each that fits in what the triangle and time budgets leave (at least one
  // build a frame, so a mesh larger than the budget still comes); marks the resident ones
  // used at `frame`; then evicts while over the memory budget. The triangle budget builds
  // the same set from the same inputs on any machine; the time budget's set depends on the
  // machine's speed (the first frame's first mesh is built alone to measure it).
  BlasFrameWork prepare(std::span<const std::uint32_t> needed, std::uint32_t frame);

  // The mesh's BLAS, or 0 while it is not resident.
  VkDeviceAddress address(std::uint32_t mesh) const;
  std::uint64_t residentBytes() const { return residentBytes_; }
  std::uint32_t residentCount() const { return residentCount_; }

 private:
  const VulkanContext& context_;
  const GpuBuffer& vertices_;
  std::uint32_t vertexStride_;
  const GpuBuffer& indices_;
  std::vector<MeshGeometry> meshes_;
  std::uint64_t budgetBytes_;
  std::uint64_t buildTriangles_;
  double buildMilliseconds_;
  // What the builds so far took: the time budget's rate, triangles per GPU millisecond.
  double measuredTriangles_ = 0.0;
  double measuredMilliseconds_ = 0.0;
  std::uint32_t keepFrames_;
  std::vector<std::optional<AccelerationStructure>> blases_;
  std::vector<std::uint32_t> lastUsed_;  // frame + 1; 0: never
  std::uint64_t residentBytes_ = 0;
  std::uint32_t residentCount_ = 0;
};

}  // namespace memograph::runtime
