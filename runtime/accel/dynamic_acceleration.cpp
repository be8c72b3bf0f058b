#include "runtime/accel/dynamic_acceleration.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

namespace {

// The unit cube's 8 corners and 12 triangles.
constexpr std::array<float, 24> kCubeCorners = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                                                0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
constexpr std::array<std::uint32_t, 36> kCubeTriangles = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6,
                                                          0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7,
                                                          0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};

// The unit cube stretched over a box; a flat box gets a millimetre of thickness so that
// rays still cross it.
glm::mat4 boxTransform(const Bounds& box) {
  glm::vec3 extent = glm::max(box.hi - box.lo, glm::vec3(1e-3f));
  return glm::scale(glm::translate(glm::mat4(1.0f), box.lo), extent);
}

// The BLAS cache's meshes: the scene's, then with mesh LODs on their levels (SceneBuffers::
// lodGeometry, level-major, so that the cache's lowest-index-first builds the finer first).
std::vector<MeshGeometry> cacheGeometry(const SceneBuffers& buffers,
                                        const CullingOptions& options) {
  std::vector<MeshGeometry> geometry = buffers.geometry;
  if (options.meshLods)
    geometry.insert(geometry.end(), buffers.lodGeometry.begin(), buffers.lodGeometry.end());
  return geometry;
}

}  // namespace

DynamicAccelerationStructures::DynamicAccelerationStructures(
    const VulkanContext& context, const Scene& scene, SceneBuffers& buffers,
    const CullingOptions& options, const std::filesystem::path& shaderCacheDirectory,
    std::uint32_t feedbackPathWeight)
    : context_(context),
      options_(options),
      culling_(scene, options),
      blasCache_(context, buffers.vertices, sizeof(gpu::Vertex), buffers.indices,
                 cacheGeometry(buffers, options), options.blasBudgetBytes,
                 options.blasBuildTriangles, options.blasBuildMilliseconds, options.blasKeepFrames),
      animated_(context, scene, buffers, options.blasRebuildEvery, shaderCacheDirectory),
      feedbackPathWeight_(feedbackPathWeight) {
  meshCount_ = static_cast<std::uint32_t>(scene.meshes.size());
  shownLods_.assign(scene.instances.size(), 0);
  if (options_.showsMeshLods() && !buffers.lodGeometry.empty()) {
    lods_.emplace(scene, culling_.bounds(), options_.lodPixelError);
    meshLodIds_ = buffers.meshLodIds;
    for (const Instance& instance : scene.instances)
      uploadedLodMeshes_.push_back(instance.mesh);
    lodMeshStaging_ = hostBuffer(
        context, std::max<VkDeviceSize>(16, scene.instances.size() * sizeof(std::uint32_t)),
        VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    instanceBuffer_ = &buffers.instances;
  }
  // Each instance's TLAS record, made once: a frame copies it and fills in the BLAS address.
  for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    instanceMeshes_.push_back(instance.mesh);
    instanceRecords_.push_back(
        instanceRecord(instance.objectToWorld, i,
                       instance.castsShadow ? gpu::kMaskSurface : gpu::kMaskLightQuad, 0));
  }
  if (hitFeedbackOn()) {
    boxVertices_ =
        uploadBuffer(context, kCubeCorners.data(), sizeof kCubeCorners, kAccelerationBuildInput);
    boxIndices_ = uploadBuffer(context, kCubeTriangles.data(), sizeof kCubeTriangles,
                               kAccelerationBuildInput);
    const MeshGeometry cube{0, 8, 0, 12};
    box_ = buildCompactedBlases(context, boxVertices_, 3 * sizeof(float), boxIndices_,
                                std::span<const MeshGeometry>(&cube, 1));
    // The counting boxes' records, made once too: each instance's, then each hitbox's.
    const VkDeviceAddress box = box_.blases.front().address();
    for (std::uint32_t i = 0; i < culling_.instanceCount(); ++i)
      boxRecords_.push_back(
          instanceRecord(boxTransform(culling_.bounds()[i]), i, gpu::kMaskCountingBox, box));
    for (std::uint32_t h = 0; h < culling_.hitboxCount(); ++h)
      boxRecords_.push_back(instanceRecord(boxTransform(culling_.hitboxBounds(h)),
                                           culling_.instanceCount() + h, gpu::kMaskCountingBox,
                                           box));
  }
  tlas_ = std::make_unique<TopLevelStructure>(context, culling_.instanceCount());
  if (hitFeedbackOn())
    boxTlas_ = std::make_unique<TopLevelStructure>(context, culling_.counterCount());
  // The counters live on the device (the trace's atomics) and are copied to a host buffer
  // after each frame. One more uint after them (and after the footprints): the trace's own tally of
  // the counts it made (path_tracer.glsl: the buffer's last uint), to check that the counts it
  // buffers all arrive (FrameStats::feedbackCountsArrived); so the size is exact with feedback, and
  // 16 bytes without, only for the binding to be valid. The footprints (one per instance) sit
  // between the counters and the tally.
  const VkDeviceSize counterBytes =
      hitFeedbackOn() ? VkDeviceSize(culling_.counterCount() + culling_.instanceCount() + 1) *
                            sizeof(std::uint32_t)
                      : 16;
  hitFeedback_ = GpuBuffer(context, counterBytes,
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  hitReadback_ = hostBuffer(context, counterBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
}

bool DynamicAccelerationStructures::prepareLook(const Camera& camera, float aspect,
                                                std::uint32_t frame, float seconds,
                                                std::uint32_t pixelStep, FrameStats& stats) {
  using Clock = std::chrono::steady_clock;
  const auto stateStart = Clock::now();
  if (!culling_.wantsLook(camera, aspect)) {
    stats.cullingHostMilliseconds =
        std::chrono::duration<double, std::milli>(Clock::now() - stateStart).count();
    return false;
  }
  culling_.look(camera, aspect);
  // The look's probe traces with the LODs the camera's distances choose (no feedback yet).
  if (lods_ && !lodsChosen_) {
    lods_->update(camera, pixelAngle(camera), {});
    lodsChosen_ = true;
  }
  lookCountsPending_ = true;
  const double step = std::max(pixelStep, 1u);
  lookRayWeight_ = 1.0 / (step * step);
  prepareStructures(frame, seconds, stats, stateStart);
  stats.looks = 1;
  return true;
}

void DynamicAccelerationStructures::prepareFrame(const Camera& camera, float aspect,
                                                 std::uint32_t frame, float seconds,
                                                 std::uint64_t previousRays, FrameStats& stats) {
  const auto stateStart = std::chrono::steady_clock::now();
  std::vector<std::uint32_t> hits;
  // The counters of the last trace, a look's just before or the last frame's (none before
  // frame 0 without a look). A quiet frame's (--feedback-every) are read too, for its tally,
  // which its pipeline leaves 0, but they are no counts to act on.
  std::vector<std::uint32_t> footprints;
  if (hitFeedbackOn() && (frame > 0 || lookCountsPending_)) {
    hits.resize(culling_.counterCount() + culling_.instanceCount() + 1);
    hitReadback_.read(hits.data(), hits.size() * sizeof(std::uint32_t));
    stats.feedbackCounts = hits.back();
    hits.pop_back();
    footprints.assign(hits.begin() + culling_.counterCount(), hits.end());
    hits.resize(culling_.counterCount());
    for (const std::uint32_t h : hits)
      stats.feedbackCountsArrived += h;
    if (!lookCountsPending_ && !frameCounted_) {
      hits.clear();
      footprints.clear();
    }
  }
  culling_.update(
      camera, aspect, hits, previousRays,
      lookCountsPending_ ? lookRayWeight_ : double(options_.feedbackStride * feedbackPathWeight_));
  // The LODs from the counting frame's footprints; between counting frames the choice keeps
  // them, and what has no feedback follows its distance.
  if (lods_ && (!lodsChosen_ || !footprints.empty() || !hitFeedbackOn())) {
    lods_->update(camera, pixelAngle(camera), footprints);
    lodsChosen_ = true;
  }
  lookCountsPending_ = false;
  frameCounted_ = hitFeedbackOn() && frame % options_.feedbackEvery == 0;
  prepareStructures(frame, seconds, stats, stateStart);
}

void DynamicAccelerationStructures::prepareStructures(
    std::uint32_t frame, float seconds, FrameStats& stats,
    std::chrono::steady_clock::time_point stateStart) {
  using Clock = std::chrono::steady_clock;
  // The meshes the active instances use: animated ones are moved and updated (all of them
  // without culling), the others come from the BLAS cache.
  const std::vector<InstanceState>& states = culling_.states();
  std::vector<std::uint32_t> needed;
  std::vector<std::uint8_t> animatedNeeded(meshCount_, 0);
  for (std::uint32_t i = 0; i < states.size(); ++i) {
    if (states[i] != InstanceState::Active)
      continue;
    if (animated_.address(instanceMeshes_[i])) {
      animatedNeeded[instanceMeshes_[i]] = 1;
      continue;
    }
    const std::uint32_t wanted = lods_ ? lods_->wanted()[i] : 0;
    needed.push_back(lodMesh(i, wanted));
    // A LOD switch waits for its BLAS under the build budgets (seeds/001 §3.3.1: "LOD change
    // requests are only processed up to a certain number of BLAS builds or a number of
    // processed primitives"): meanwhile the level shown keeps its BLAS, if it has one.
    const std::uint32_t shown = lodMesh(i, shownLods_[i]);
    if (shownLods_[i] != wanted && blasCache_.address(shown))
      needed.push_back(shown);
  }
  double hostMilliseconds =
      std::chrono::duration<double, std::milli>(Clock::now() - stateStart).count();
  const BlasFrameWork work = blasCache_.prepare(needed, frame);
  const AnimatedFrameWork moved = animated_.prepare(
      seconds, frame,
      options_.mode == CullingMode::None ? std::vector<std::uint8_t>{} : animatedNeeded);

  const auto recordStart = Clock::now();
  // Each mesh's BLAS this frame (0: not resident; its instances wait for the build).
  std::vector<VkDeviceAddress> meshAddresses(meshCount_, 0);
  for (std::uint32_t m = 0; m < meshCount_; ++m) {
    meshAddresses[m] = animated_.address(m);
    if (!meshAddresses[m])
      meshAddresses[m] = blasCache_.address(m);
  }
  // Each active instance's BLAS: its wanted LOD's, else (its build waits) the one it shows,
  // else none (it waits); its ids.z follows what the TLAS holds.
  lodMeshCopies_.clear();
  auto* staging = lods_ ? static_cast<std::uint32_t*>(lodMeshStaging_.mapped()) : nullptr;
  const auto blasOf = [&](std::uint32_t i) -> VkDeviceAddress {
    if (!lods_ || animated_.address(instanceMeshes_[i]))
      return meshAddresses[instanceMeshes_[i]];
    std::uint32_t level = lods_->wanted()[i];
    VkDeviceAddress blas = blasCache_.address(lodMesh(i, level));
    if (!blas && blasCache_.address(lodMesh(i, shownLods_[i]))) {
      level = shownLods_[i];
      blas = blasCache_.address(lodMesh(i, level));
    }
    if (!blas)
      return 0;
    shownLods_[i] = static_cast<std::uint8_t>(level);
    const std::uint32_t mesh = lodMesh(i, level);
    if (uploadedLodMeshes_[i] != mesh) {
      uploadedLodMeshes_[i] = mesh;
      staging[i] = mesh;
      lodMeshCopies_.push_back({VkDeviceSize(i) * sizeof(std::uint32_t),
                                VkDeviceSize(i) * sizeof(gpu::Instance) +
                                    offsetof(gpu::Instance, ids) + 2 * sizeof(std::uint32_t),
                                sizeof(std::uint32_t)});
    }
    return blas;
  };
  // Under LiPaC an inactive hitbox with instances stands in the boxes' TLAS.
  const auto boxed = [&](std::uint32_t h) {
    return hitFeedbackOn() && culling_.hitboxUsed(h) && !culling_.hitboxActive(h);
  };
  // The TLAS records: active instances whose BLAS is resident; the counting boxes' TLAS:
  // omitted instances, then boxed hitboxes, written by the host into the mapped records.
  VkAccelerationStructureInstanceKHR* records = tlas_->records();
  VkAccelerationStructureInstanceKHR* boxes = boxTlas_ ? boxTlas_->records() : nullptr;
  std::uint32_t n = 0, boxCount = 0;
  std::uint32_t waitingInstances = 0;
  for (std::uint32_t i = 0; i < states.size(); ++i) {
    if (states[i] == InstanceState::Active) {
      const VkDeviceAddress blas = blasOf(i);
      if (!blas) {
        ++waitingInstances;
        continue;
      }
      records[n] = instanceRecords_[i];
      records[n].accelerationStructureReference = blas;
      ++n;
    } else if (states[i] == InstanceState::Omitted && hitFeedbackOn()) {
      if (boxes)
        boxes[boxCount] = boxRecords_[i];
      ++boxCount;
    }
  }
  for (std::uint32_t h = 0; h < culling_.hitboxCount(); ++h) {
    if (!boxed(h))
      continue;
    if (boxes)
      boxes[boxCount] = boxRecords_[culling_.instanceCount() + h];
    ++boxCount;
  }
  boxRecordCount_ = boxCount;
  hostMilliseconds += std::chrono::duration<double, std::milli>(Clock::now() - recordStart).count();
  stats.cullingHostMilliseconds = hostMilliseconds;
  records_ = n;

  const CullingCounts& counts = culling_.counts();
  stats.activeInstances = counts.active - waitingInstances;
  stats.waitingInstances = waitingInstances;
  stats.omittedInstances = counts.omitted;
  stats.inactiveInstances = counts.inactive;
  stats.hitboxes = counts.hitboxes;
  stats.activeHitboxes = counts.activeHitboxes;
  stats.instanceStateChanges = counts.changes;
  stats.tlasRecords = n + boxCount;
  stats.blasBytes = blasCache_.residentBytes() + box_.bytes + animated_.bytes();
  stats.tlasBytes = tlas_->bytes() + (boxTlas_ ? boxTlas_->bytes() : 0);
  stats.asScratchBytes = tlas_->scratchBytes() + (boxTlas_ ? boxTlas_->scratchBytes() : 0) +
                         work.scratchBytes + animated_.scratchBytes();
  stats.blasBuilds = work.builds + moved.rebuilds;
  stats.blasUpdates = moved.updates;
  stats.blasEvictions = work.evictions;
  stats.blasBuildMilliseconds = work.gpuMilliseconds;
}

float DynamicAccelerationStructures::pixelAngle(const Camera& camera) const {
  return pixelSpreadAngle(camera, options_.imageHeight ? options_.imageHeight : 1080u);
}

std::uint32_t DynamicAccelerationStructures::lodMesh(std::uint32_t instance,
                                                     std::uint32_t level) const {
  const std::uint32_t mesh = instanceMeshes_[instance];
  if (level == 0 || mesh >= meshLodIds_.size() || level > meshLodIds_[mesh].size())
    return mesh;
  return meshLodIds_[mesh][level - 1];
}

void DynamicAccelerationStructures::recordClears(VkCommandBuffer commands) const {
  if (!hitFeedbackOn())
    return;
  vkCmdFillBuffer(commands, hitFeedback_.buffer(), 0, VK_WHOLE_SIZE, 0);
  // The footprints start at "none" (kNoFootprint), which any counted hit's atomicMin lowers.
  vkCmdFillBuffer(commands, hitFeedback_.buffer(),
                  VkDeviceSize(culling_.counterCount()) * sizeof(std::uint32_t),
                  VkDeviceSize(culling_.instanceCount()) * sizeof(std::uint32_t), kNoFootprint);
}

void DynamicAccelerationStructures::recordLodMeshes(VkCommandBuffer commands) const {
  if (lodMeshCopies_.empty())
    return;
  vkCmdCopyBuffer(commands, lodMeshStaging_.buffer(), instanceBuffer_->buffer(),
                  static_cast<std::uint32_t>(lodMeshCopies_.size()), lodMeshCopies_.data());
  // The trace reads ids.z after the TLAS build's barrier; this one orders the copy before it.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void DynamicAccelerationStructures::recordTlasBuild(VkCommandBuffer commands,
                                                    VkQueryPool timestamps,
                                                    std::uint32_t first) const {
  if (timestamps)
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, first);
  recordLodMeshes(commands);
  animated_.record(commands);
  if (timestamps)
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                        timestamps, first + 1);
  tlas_->recordBuild(commands, records_);
  if (boxTlas_)
    boxTlas_->recordBuild(commands, boxRecordCount_);
  if (timestamps)
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                        timestamps, first + 2);
}

void DynamicAccelerationStructures::recordAfterTrace(VkCommandBuffer commands) const {
  if (!hitFeedbackOn())
    return;
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);
  VkBufferCopy copy{0, 0, hitFeedback_.size()};
  vkCmdCopyBuffer(commands, hitFeedback_.buffer(), hitReadback_.buffer(), 1, &copy);
}

}  // namespace memograph::runtime
