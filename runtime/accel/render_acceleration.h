// The acceleration-structure stage of Renderer::render and its part of every frame: the
// scene's BLASes and TLAS built once (no culling, nothing animated), or rebuilt each frame
// from what culling keeps (DynamicAccelerationStructures, seeds/001 §3.3), with LiPaC's looks
// and per-frame culling updates, and the frame's structure figures either way.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "runtime/accel/acceleration_structures.h"
#include "runtime/accel/dynamic_acceleration.h"
#include "runtime/accel/scene_culling.h"
#include "runtime/host/image.h"
#include "runtime/scene/scene.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/trace/render_stats.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

class RenderAcceleration {
 public:
  // Timestamp queries a frame's builds write from their first on (recordBuild).
  static constexpr std::uint32_t kBuildTimestamps = 3;

  // Builds every BLAS and the TLAS, or prepares the per-frame structures; fills `stats`'s
  // acceleration-structure figures known now. `scene` and `buffers` must outlive it.
  // `feedbackPathWeight`: what a counted path's ray weighs (RenderPlan).
  RenderAcceleration(const VulkanContext& context, const Scene& scene, SceneBuffers& buffers,
                     const CullingOptions& options,
                     const std::filesystem::path& shaderCacheDirectory,
                     std::uint32_t feedbackPathWeight, RenderStats& stats);

  // The trace's bindings: the TLAS, LiPaC's counters (a dummy without) and counting boxes.
  VkAccelerationStructureKHR tlas() const;
  const GpuBuffer& hitFeedback() const;
  VkAccelerationStructureKHR countingBoxes() const;
  bool hitFeedbackOn() const { return dynamic_ && dynamic_->hitFeedbackOn(); }
  // Whether the TLAS is rebuilt each frame (recordBuild writes timestamps then).
  bool rebuiltEachFrame() const { return dynamic_.has_value(); }
  // The frame prepareFrame prepared counts LiPaC's hits.
  bool frameCounts() const { return dynamic_ && dynamic_->frameCounts(); }

  // LiPaC's look (SceneCulling::look) before frame `frame`, where the culling wants one for
  // this camera, its probe one path per pixelStep x pixelStep pixels: fills `look` as
  // prepareFrame does and returns true.
  bool prepareLook(const Camera& camera, float aspect, std::uint32_t frame, float seconds,
                   std::uint32_t pixelStep, FrameStats& look);
  // Before frame `frame`'s submit: the per-frame culling update (the last trace's counters,
  // `previousRays` of them) and the structures it keeps; fills the frame's culling and
  // structure figures.
  void prepareFrame(const Camera& camera, float aspect, std::uint32_t frame, float seconds,
                    std::uint64_t previousRays, FrameStats& stats);

  // In a frame's command buffer: the counters' clears (before the caller's barrier), the
  // builds before the trace (timestamps from `firstTimestamp` on, kBuildTimestamps of them,
  // where `timestamps` is not VK_NULL_HANDLE), and the counters' copy after it.
  void recordClears(VkCommandBuffer commands) const;
  void recordBuild(VkCommandBuffer commands, VkQueryPool timestamps,
                   std::uint32_t firstTimestamp) const;
  void recordAfterTrace(VkCommandBuffer commands) const;

  // Folds a finished frame's figures into the render's (the peak of what was resident).
  void addFrame(const FrameStats& frame, RenderStats& stats) const;
  // Culled renders: each instance's state in the last frame (empty otherwise), and its top
  // view from `camera`, `size` pixels a side (empty without culling or at size 0).
  std::vector<InstanceState> instanceStates() const;
  // Culled renders with mesh LODs: each instance's LOD when last in the TLAS (empty otherwise).
  std::vector<std::uint8_t> instanceLods() const;
  HdrImage cullingView(const Camera& camera, std::uint32_t size) const;

 private:
  std::optional<SceneAccelerationStructures> static_;
  std::optional<DynamicAccelerationStructures> dynamic_;
  GpuBuffer noHitFeedback_;  // the counters' binding where nothing counts
};

}  // namespace memograph::runtime
