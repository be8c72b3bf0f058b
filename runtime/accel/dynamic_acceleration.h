// The acceleration structures of a render whose TLAS changes every frame (seeds/001 §3.3):
// a culled render (--culling frustum|lipac), or a scene with animated meshes. Every frame,
// SceneCulling decides which instances the TLAS holds from the camera and the last frame's
// hit feedback, the BlasCache builds and evicts their BLASes, the animated meshes the frame
// uses are moved and their BLASes updated (AnimatedBlases), and the TLAS is rebuilt from the
// active instances plus LiPaC's counting boxes (one static unit-cube BLAS, transformed to
// each omitted instance's or inactive hitbox's bounds). With mesh LODs (Scene::meshLods,
// CullingOptions::meshLods) an instance shows the LOD InstanceLodChoice picks from the ray
// cones that reached it, each (mesh, LOD) one BLAS of the cache (seeds/001 §3.3.1).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "runtime/accel/acceleration_structures.h"
#include "runtime/accel/animated_blases.h"
#include "runtime/accel/blas_cache.h"
#include "runtime/accel/lod_choice.h"
#include "runtime/accel/scene_culling.h"
#include "runtime/scene/scene.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/trace/render_stats.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

class DynamicAccelerationStructures {
 public:
  // `scene` and `buffers` must outlive this object. `shaderCacheDirectory`: where the animated
  // meshes' vertex pass is cached (none when empty). `feedbackPathWeight`: what a counted
  // path's ray weighs beside the blocks' stride (CullingOptions::feedbackPaths: P / N where N
  // of a pixel's P paths count; the renderer knows P).
  DynamicAccelerationStructures(const VulkanContext& context, const Scene& scene,
                                SceneBuffers& buffers, const CullingOptions& options,
                                const std::filesystem::path& shaderCacheDirectory,
                                std::uint32_t feedbackPathWeight = 1);

  VkAccelerationStructureKHR tlas() const { return tlas_->handle(); }
  // LiPaC's counting boxes (binding kBindingCountingBoxes); VK_NULL_HANDLE without LiPaC.
  VkAccelerationStructureKHR countingBoxes() const {
    return boxTlas_ ? boxTlas_->handle() : VK_NULL_HANDLE;
  }
  // LiPaC's counters (binding kBindingHitFeedback): SceneCulling::counterCount() uints, one
  // footprint per instance (hit_counters.glsl; the mesh LODs' choice), then the trace's tally
  // of the counts it made.
  const GpuBuffer& hitFeedback() const { return hitFeedback_; }
  bool hitFeedbackOn() const { return options_.mode == CullingMode::Lipac; }
  // Whether the frame prepareFrame prepared counts (CullingOptions::feedbackEvery): the
  // renderer then traces it with the feedback's pipeline, and the next prepareFrame acts on
  // its counters.
  bool frameCounts() const { return frameCounted_; }
  const SceneCulling& culling() const { return culling_; }
  // Each instance's LOD when last in the TLAS (0: its mesh, or never in it).
  const std::vector<std::uint8_t>& shownLods() const { return shownLods_; }
  bool meshLodsOn() const { return lods_.has_value(); }

  // Before frame `frame`'s submit: reads the last frame's counters (`previousRays`: the rays
  // it traced), updates the instance states, builds and evicts BLASes and writes the TLAS
  // records. Fills the frame's culling fields of `stats`.
  void prepareFrame(const Camera& camera, float aspect, std::uint32_t frame, float seconds,
                    std::uint64_t previousRays, FrameStats& stats);
  // LiPaC's look (SceneCulling::look), where the culling wants one for this camera: the
  // probe's states and structures, for one trace of the frame's camera whose counters the
  // frame's prepareFrame then reads; fills `stats` as prepareFrame does, with looks = 1.
  // `pixelStep`: the probe traces one path per pixelStep x pixelStep pixels. Returns whether
  // it prepared one; the check's host time is in stats.cullingHostMilliseconds either way
  // (the frame adds it to its own).
  bool prepareLook(const Camera& camera, float aspect, std::uint32_t frame, float seconds,
                   std::uint32_t pixelStep, FrameStats& stats);
  // In the frame's command buffer, with the other clears (the caller's barrier orders them
  // before the trace): zeroes the hit counters.
  void recordClears(VkCommandBuffer commands) const;
  // Before the trace: moves the animated meshes and updates their BLASes, then builds the
  // TLAS and makes it visible to the trace; with `timestamps`, writes queries `first`
  // (start), `first + 1` (after the animated BLASes) and `first + 2` (after the TLAS).
  void recordTlasBuild(VkCommandBuffer commands, VkQueryPool timestamps, std::uint32_t first) const;
  // Before the TLAS build (recordTlasBuild does it): copies the LOD mesh of each instance
  // whose LOD changed into its gpu::Instance::ids.z, which the shading reads the hit's
  // triangle from.
  void recordLodMeshes(VkCommandBuffer commands) const;
  // After the trace: copies the counters where prepareFrame reads them.
  void recordAfterTrace(VkCommandBuffer commands) const;

 private:
  // A pixel's angle for the LODs' distance choice (CullingOptions::imageHeight).
  float pixelAngle(const Camera& camera) const;
  // The BLAS cache's mesh of an instance at `level` (its own mesh at 0).
  std::uint32_t lodMesh(std::uint32_t instance, std::uint32_t level) const;
  // After the states: builds and evicts BLASes and writes the TLAS records (both prepares).
  void prepareStructures(std::uint32_t frame, float seconds, FrameStats& stats,
                         std::chrono::steady_clock::time_point stateStart);

  const VulkanContext& context_;
  CullingOptions options_;
  SceneCulling culling_;
  std::uint32_t meshCount_ = 0;
  std::vector<std::uint32_t> instanceMeshes_;
  // Mesh LODs: the choice (none without LODs), the BLAS cache's ids of each mesh's levels
  // (SceneBuffers::meshLodIds), each instance's LOD in the TLAS and the mesh id its
  // gpu::Instance::ids.z holds, and the copies that bring ids.z up to date this frame.
  std::optional<InstanceLodChoice> lods_;
  std::vector<std::vector<std::uint32_t>> meshLodIds_;
  std::vector<std::uint8_t> shownLods_;
  std::vector<std::uint32_t> uploadedLodMeshes_;
  GpuBuffer lodMeshStaging_;  // one uint per instance, host-visible
  std::vector<VkBufferCopy> lodMeshCopies_;
  const GpuBuffer* instanceBuffer_ = nullptr;
  bool lodsChosen_ = false;  // the choice has run (the first look's or frame's distances)
  // TLAS records made once: each instance's (BLAS address 0, filled in per frame) and, under
  // LiPaC, each instance's counting box then each hitbox's, copied into the TLAS's records
  // every frame.
  std::vector<VkAccelerationStructureInstanceKHR> instanceRecords_;
  std::vector<VkAccelerationStructureInstanceKHR> boxRecords_;
  BlasCache blasCache_;
  AnimatedBlases animated_;
  // The unit cube [0, 1]^3 that counting boxes instance.
  GpuBuffer boxVertices_;
  GpuBuffer boxIndices_;
  CompactedBlases box_;
  std::unique_ptr<TopLevelStructure> tlas_;
  std::uint32_t records_ = 0;
  std::unique_ptr<TopLevelStructure> boxTlas_;  // LiPaC only
  std::uint32_t boxRecordCount_ = 0;
  GpuBuffer hitFeedback_;
  GpuBuffer hitReadback_;
  bool lookCountsPending_ = false;  // the next prepareFrame reads a look's counters
  double lookRayWeight_ = 1.0;      // SceneCulling::update's rayWeight for the look's counters
  bool frameCounted_ = false;       // the frame last prepared counts (frameCounts)
  const std::uint32_t feedbackPathWeight_;
};

}  // namespace memograph::runtime
