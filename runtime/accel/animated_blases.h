// The BLASes of animated meshes (Scene::animatedMeshes; seeds/001 §3.3.1): built once with
// ALLOW_UPDATE and not compacted ("we only compact static BLASes"), then every frame the
// vertex pass (vertex_motion.comp) moves the meshes' vertices in the shared vertex buffer
// (Scene::animatedMotions, normals from the moved triangles), and the BLASes are updated in
// place, with a full rebuild every `rebuildEvery` frames because refits degrade the tree.
// As §3.3.1 batches them: one dispatch for every mesh, one barrier, then every build. In a
// culled render only the meshes an active instance uses are moved; one left behind is
// rebuilt when it is needed again.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "runtime/accel/acceleration_structures.h"
#include "runtime/scene/scene.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

struct AnimatedFrameWork {
  std::uint32_t updates = 0;
  std::uint32_t rebuilds = 0;
};

class AnimatedBlases {
 public:
  // `buffers` must outlive this object. rebuildEvery >= 1. The vertex pass's SPIR-V is
  // cached in `shaderCacheDirectory` (none when empty), as the renderer's shaders are.
  AnimatedBlases(const VulkanContext& context, const Scene& scene, SceneBuffers& buffers,
                 std::uint32_t rebuildEvery, const std::filesystem::path& shaderCacheDirectory);

  bool empty() const { return meshes_.empty(); }
  // The mesh's BLAS, or 0 when the mesh is not animated.
  VkDeviceAddress address(std::uint32_t mesh) const;
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t scratchBytes() const { return scratch_.size(); }

  // Host side, before frame `frame`'s submit: plans the vertex pass that moves the animated
  // meshes `needed` marks (indexed by mesh; every one when it is empty) to time `seconds`,
  // and their BLASes' updates or rebuilds.
  AnimatedFrameWork prepare(float seconds, std::uint32_t frame,
                            const std::vector<std::uint8_t>& needed);
  // In the frame's command buffer before the TLAS build: the vertex pass, then the BLAS
  // updates and rebuilds, each with the barrier that orders it (nothing when prepare
  // planned nothing).
  void record(VkCommandBuffer commands) const;

 private:
  struct Animated {
    std::uint32_t mesh = 0;
    std::size_t k = 0;            // index into Scene::animatedMeshes
    std::uint32_t firstRest = 0;  // its first vertex in rest_
    MeshGeometry geometry;
    AccelerationStructure blas;
    VkDeviceSize scratchOffset = 0;
    std::uint32_t builtAfter = 0;  // 1 + the frame of its last (re)build; 0: the first
    bool current = false;          // its BLAS matches the last positions written
    float normalSign = 1.0f;       // turns the winding's normals to the mesh's own side
  };

  const VulkanContext& context_;
  const Scene& scene_;
  SceneBuffers& buffers_;
  std::uint32_t rebuildEvery_;
  std::vector<Animated> meshes_;
  std::vector<std::int32_t> slotOfMesh_;  // -1: not animated
  GpuBuffer rest_;     // gpu::VertexMotionRest per animated vertex, mesh after mesh
  GpuBuffer corners_;  // the triangles around each rest vertex: rest indices (uvec4)
  GpuBuffer jobs_;     // host-visible: this frame's gpu::VertexMotionJob, one per moved mesh
  PushConstantPass pass_;
  GpuBuffer scratch_;
  std::uint64_t bytes_ = 0;
  // The frame's plan, read by record().
  float seconds_ = 0.0f;
  std::uint32_t movedMeshes_ = 0;       // jobs written this frame
  std::uint32_t movedMaxVertices_ = 0;  // the largest of their vertex counts
  std::vector<std::size_t> planned_;    // slots to build this frame
  std::vector<std::uint8_t> plannedUpdate_;
};

}  // namespace memograph::runtime
