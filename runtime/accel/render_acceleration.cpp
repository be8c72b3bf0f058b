#include "runtime/accel/render_acceleration.h"

#include <algorithm>

#include "runtime/accel/culling_view.h"
#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

RenderAcceleration::RenderAcceleration(const VulkanContext& context, const Scene& scene,
                                       SceneBuffers& buffers, const CullingOptions& options,
                                       const std::filesystem::path& shaderCacheDirectory,
                                       std::uint32_t feedbackPathWeight, RenderStats& stats) {
  // Animated meshes move every frame: their BLASes are updated and the TLAS rebuilt, as in
  // a culled render.
  const bool animated = !scene.animatedMeshes.empty() && !scene.animatedMotions.empty();
  if (options.mode == CullingMode::None && !animated) {
    static_.emplace(context, buffers.vertices, sizeof(gpu::Vertex), buffers.indices,
                    buffers.geometry, buffers.placements);
    stats.accelerationStructures = static_->stats();
    noHitFeedback_ = GpuBuffer(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  } else {
    dynamic_.emplace(context, scene, buffers, options, shaderCacheDirectory, feedbackPathWeight);
    stats.accelerationStructures.blasCount = static_cast<std::uint32_t>(buffers.geometry.size());
    stats.accelerationStructures.instanceCount = static_cast<std::uint32_t>(scene.instances.size());
  }
}

VkAccelerationStructureKHR RenderAcceleration::tlas() const {
  return static_ ? static_->tlas() : dynamic_->tlas();
}

const GpuBuffer& RenderAcceleration::hitFeedback() const {
  return dynamic_ ? dynamic_->hitFeedback() : noHitFeedback_;
}

VkAccelerationStructureKHR RenderAcceleration::countingBoxes() const {
  return dynamic_ ? dynamic_->countingBoxes() : VK_NULL_HANDLE;
}

bool RenderAcceleration::prepareLook(const Camera& camera, float aspect, std::uint32_t frame,
                                     float seconds, std::uint32_t pixelStep, FrameStats& look) {
  return dynamic_ && dynamic_->prepareLook(camera, aspect, frame, seconds, pixelStep, look);
}

void RenderAcceleration::prepareFrame(const Camera& camera, float aspect, std::uint32_t frame,
                                      float seconds, std::uint64_t previousRays,
                                      FrameStats& stats) {
  if (dynamic_) {
    dynamic_->prepareFrame(camera, aspect, frame, seconds, previousRays, stats);
    return;
  }
  const AccelerationStructureStats& a = static_->stats();
  stats.activeInstances = stats.tlasRecords = a.instanceCount;
  stats.blasBytes = a.blasBytes;
  stats.tlasBytes = a.tlasBytes;
  stats.asScratchBytes = static_->residentScratchBytes();
}

void RenderAcceleration::recordClears(VkCommandBuffer commands) const {
  if (dynamic_)
    dynamic_->recordClears(commands);
}

void RenderAcceleration::recordBuild(VkCommandBuffer commands, VkQueryPool timestamps,
                                     std::uint32_t firstTimestamp) const {
  if (dynamic_)
    dynamic_->recordTlasBuild(commands, timestamps, firstTimestamp);
}

void RenderAcceleration::recordAfterTrace(VkCommandBuffer commands) const {
  if (dynamic_)
    dynamic_->recordAfterTrace(commands);
}

void RenderAcceleration::addFrame(const FrameStats& frame, RenderStats& stats) const {
  if (!dynamic_)
    return;
  auto& a = stats.accelerationStructures;
  a.blasBytes = std::max(a.blasBytes, frame.blasBytes);
  a.tlasBytes = frame.tlasBytes;
  a.scratchBytes = std::max(a.scratchBytes, frame.asScratchBytes);
  a.buildMilliseconds += frame.blasBuildMilliseconds + frame.tlasBuildMilliseconds;
}

std::vector<InstanceState> RenderAcceleration::instanceStates() const {
  return dynamic_ ? dynamic_->culling().states() : std::vector<InstanceState>{};
}

std::vector<std::uint8_t> RenderAcceleration::instanceLods() const {
  return dynamic_ && dynamic_->meshLodsOn() ? dynamic_->shownLods() : std::vector<std::uint8_t>{};
}

HdrImage RenderAcceleration::cullingView(const Camera& camera, std::uint32_t size) const {
  return dynamic_ && size > 0 ? cullingTopView(dynamic_->culling(), camera, size, instanceLods())
                              : HdrImage{};
}

}  // namespace memograph::runtime
