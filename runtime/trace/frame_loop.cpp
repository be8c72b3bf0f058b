#include "runtime/trace/frame_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

// The tracer's own timestamps follow the trace's (0, 1) and the builds' (2-4).
constexpr std::uint32_t kFirstBuildTimestamp = 2;
// A look after the render's first traces one path per block of this many pixels square.
constexpr std::uint32_t kSparseLookStep = 2;
constexpr std::uint32_t kFirstTracerTimestamp =
    kFirstBuildTimestamp + RenderAcceleration::kBuildTimestamps;

bool sameCamera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.target == b.target && a.up == b.up &&
         a.verticalFovDegrees == b.verticalFovDegrees;
}

// Camera basis and the primary ray cone's spread angle (thesis §2.2: one pixel's angle).
void setCamera(gpu::FrameConstants& frame, const Camera& camera, std::uint32_t width,
               std::uint32_t height) {
  glm::vec3 forward = camera.target - camera.position;
  if (glm::dot(forward, forward) < 1e-20f)
    throw std::invalid_argument("the camera's position and target coincide");
  if (!(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f))
    throw std::invalid_argument("the camera's vertical field of view must be in (0, 180) degrees");
  forward = glm::normalize(forward);
  glm::vec3 right = glm::cross(forward, camera.up);
  if (glm::dot(right, right) < 1e-12f)
    throw std::invalid_argument("the camera's up vector is parallel to its view direction");
  right = glm::normalize(right);
  glm::vec3 up = glm::cross(right, forward);
  float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  float aspect = float(width) / float(height);
  float pixelSpread = std::atan(2.0f * tanHalf / float(height));
  frame.cameraPosition = glm::vec4(camera.position, pixelSpread);
  frame.cameraRight = glm::vec4(right * tanHalf * aspect, 0.0f);
  frame.cameraUp = glm::vec4(up * tanHalf, 0.0f);
  frame.cameraForward = glm::vec4(forward, frame.cameraForward.w);
}

// The constants every frame shares; the camera, the frame's index and clocks are set per
// frame.
gpu::FrameConstants baseFrameConstants(const FrameLoopInputs& in) {
  const Scene& scene = *in.scene;
  const RenderSettings& settings = *in.settings;
  const SceneBuffers& buffers = in.resources->buffers;
  gpu::FrameConstants frame{};
  frame.environment = scene.environment.imageRgb.empty()
                          ? glm::vec4(scene.environment.constantRadiance, 0.0f)
                          : glm::vec4(1.0f, 1.0f, 1.0f, 0.0f);
  frame.image = glm::uvec4(settings.width, settings.height, 0, settings.seed);
  std::uint32_t flags = (settings.sharedPrimaryRay ? gpu::kFlagSharedPrimaryRay : 0u) |
                        (buffers.environmentWidth ? gpu::kFlagEnvironmentImage : 0u);
  frame.path = glm::uvec4(settings.pathsPerPixel, settings.raysPerPath, flags, buffers.lightCount);
  frame.environmentSize = glm::uvec4(buffers.environmentWidth, buffers.environmentHeight, 0, 0);
  // LiPaC's sampling: x the blocks' stride, z the paths that count (0: every one).
  frame.culling = glm::uvec4(in.culling->feedbackStride, 0,
                             in.plan->feedbackPathWeight > 1 ? in.culling->feedbackPaths : 0u, 0);
  std::uint32_t mipBiasBits = 0;
  std::memcpy(&mipBiasBits, &in.plan->cache.mipBias, sizeof mipBiasBits);
  frame.cache = glm::uvec4(in.cache->entryCount(), 0u, mipBiasBits, in.cache->tilesPerRow());
  return frame;
}

double milliseconds(std::uint64_t from, std::uint64_t to, double millisecondsPerTick) {
  return double(to - from) * millisecondsPerTick;
}

}  // namespace

FrameLoop::FrameLoop(const VulkanContext& context, const FrameLoopInputs& inputs)
    : context_(context), in_(inputs) {
  const RenderSettings& settings = *in_.settings;
  aspect_ = float(settings.width) / float(settings.height);
  frameBuffer_ =
      hostBuffer(context, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  accumulation_ = GpuBuffer(context, in_.plan->accumulationBytes,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                            VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  rayCounter_ = GpuBuffer(context, sizeof(gpu::Counters),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  rayReadback_ = hostBuffer(context, sizeof(gpu::Counters), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  const RenderAcceleration& accel = *in_.acceleration;
  TraceResources resources{accel.tlas(),
                           &frameBuffer_,
                           &accumulation_,
                           &rayCounter_,
                           in_.cache,
                           &in_.resources->buffers,
                           in_.resources->textures.get(),
                           &accel.hitFeedback(),
                           accel.countingBoxes()};
  in_.tracer->addResources(resources);
  descriptors_ =
      std::make_unique<TraceDescriptorSet>(context, in_.tracer->descriptorSetLayout(), resources);

  tracerTimestamps_ = in_.tracer->timestampCount(settings.pathsPerPixel, settings.raysPerPath);
  timestampCount_ = kFirstTracerTimestamp + tracerTimestamps_;
  if (context.info().timestamps) {
    VkDevice device = context.device();
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = timestampCount_;
    VkQueryPool queryPool = VK_NULL_HANDLE;
    checkVk(vkCreateQueryPool(device, &queryInfo, nullptr, &queryPool), "vkCreateQueryPool");
    timestampPool_ = VulkanHandle<VkQueryPool>(
        queryPool, [device](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });
  }
  millisecondsPerTick_ = context.info().timestampPeriodNs * 1e-6;
  frame_ = baseFrameConstants(in_);
}

void FrameLoop::submit(bool firstFrame, const FrameTrace& trace) const {
  const VkQueryPool timestamps = timestampPool_.get();
  context_.submitAndWait([&](VkCommandBuffer commands) {
    // The cache is cleared once, before the first frame: every key kCacheKeyEmpty (0),
    // every clock 0, and with it the counters that persist (occupancy, counter clock);
    // the per-frame counters and the tile log every frame. The barrier below orders them
    // before the trace.
    vkCmdFillBuffer(
        commands, rayCounter_.buffer(), 0,
        firstFrame ? VK_WHOLE_SIZE : gpu::kCountersPerFrameUints * sizeof(std::uint32_t), 0);
    in_.cache->recordClears(commands, firstFrame);
    in_.acceleration->recordClears(commands);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    if (timestamps)
      vkCmdResetQueryPool(commands, timestamps, 0, timestampCount_);
    in_.acceleration->recordBuild(commands, timestamps, kFirstBuildTimestamp);
    if (timestamps)
      vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
    in_.tracer->recordTrace(commands, descriptors_->get(), trace, timestamps,
                            kFirstTracerTimestamp);
    if (timestamps)
      vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, 1);
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    VkBufferCopy copy{0, 0, sizeof(gpu::Counters)};
    vkCmdCopyBuffer(commands, rayCounter_.buffer(), rayReadback_.buffer(), 1, &copy);
    in_.acceleration->recordAfterTrace(commands);
  });
}

std::vector<std::uint64_t> FrameLoop::readTimestamps(std::uint32_t first,
                                                     std::uint32_t count) const {
  std::vector<std::uint64_t> ticks(count, 0);
  checkVk(vkGetQueryPoolResults(context_.device(), timestampPool_.get(), first, count,
                                count * sizeof(std::uint64_t), ticks.data(), sizeof(std::uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults (timestamps)");
  return ticks;
}

gpu::Counters FrameLoop::readCounters() const {
  gpu::Counters counters{};
  rayReadback_.read(&counters, sizeof counters);
  return counters;
}

void FrameLoop::look(std::uint32_t f, const Camera& camera, bool firstLook, FrameStats& look) {
  const std::uint32_t step = firstLook ? 1u : kSparseLookStep;
  if (!in_.acceleration->prepareLook(camera, aspect_, f, frame_.cameraForward.w, step, look))
    return;
  // LiPaC's look (SceneCulling::look): one trace of this frame's camera, its image replaced
  // by the frame's, its builds, host and GPU time folded into the frame's figures, its
  // counters read by the frame's culling update. The probe traces one path a pixel and
  // counts every ray of it: it is one trace that decides what the frame holds, and with 1
  // in feedbackStride blocks counted an instance seen in a few pixels could go unseen (the
  // small city's first frame at 64x36 differed from the unculled one by 1.14 % of the
  // image's mean, against 0.78 % with every ray counted:
  // CulledRender.TheFirstLookHoldsWhatTheFirstCameraReaches). One path, not P: its image
  // is not kept, and on the H200 at P = 6 a frame with a look of P paths took 1.6-2.5x the
  // unculled frame's time (with one path 1.10x). For the same reason its paths trace no
  // shadow rays (frame.culling.w).
  //
  // After the first, a look is sparse: one path per kSparseLookStep x kSparseLookStep block
  // of pixels, at a random point of its block (its centre with --shared-primary) but with the
  // pixel's ray cone (so its cache keys and LOD footprints are the frame's), and one of its
  // rays activates what it reaches (SceneCulling::update's rayWeight). It looks for what
  // comes into view while most of the scene is already held. The first look, with nothing
  // held yet, traces every pixel.
  const glm::uvec4 framePath = frame_.path, frameCulling = frame_.culling,
                   frameImage = frame_.image;
  frame_.path.x = 1u;
  frame_.culling = glm::uvec4(1u, frame_.culling.y, 0u, gpu::kCullingLook);
  frame_.image.x = (frameImage.x + step - 1u) / step;
  frame_.image.y = (frameImage.y + step - 1u) / step;
  frameBuffer_.write(&frame_, sizeof frame_);
  FrameTrace probe;
  probe.paths = 1;
  probe.rays = in_.settings->raysPerPath;
  probe.counts = true;
  probe.look = true;
  probe.counted = {0, 1};
  probe.width = frame_.image.x;
  probe.height = frame_.image.y;
  submit(firstLook, probe);
  frame_.path = framePath;
  frame_.culling = frameCulling;
  frame_.image = frameImage;
  frameBuffer_.write(&frame_, sizeof frame_);
  previousRays_ = look.lookRays = readCounters().rays;
  if (timestampPool_) {
    const std::vector<std::uint64_t> ticks = readTimestamps(0, 5);
    look.lookMilliseconds = milliseconds(ticks[0], ticks[1], millisecondsPerTick_);
    look.blasBuildMilliseconds += milliseconds(ticks[2], ticks[3], millisecondsPerTick_);
    look.tlasBuildMilliseconds = milliseconds(ticks[3], ticks[4], millisecondsPerTick_);
  }
}

void FrameLoop::readFrame(const FrameTrace& trace, const FrameStats& look, FrameStats& stats) {
  const gpu::Counters counters = readCounters();
  stats.rays = counters.rays;
  previousRays_ = counters.rays;
  stats.cacheLookups = counters.cacheLookups;
  stats.cacheHits = counters.cacheHits;
  stats.cacheMisses = counters.cacheMisses;
  stats.cacheOccupancy = counters.cacheOccupancy;
  stats.cacheClockTicks = counters.cacheClock;
  stats.cacheTilesComputed = counters.cacheTilesComputed;
  stats.cacheDuplicateTiles = counters.cacheDuplicateTiles;
  stats.cacheTileFallbacks = counters.cacheTileFallbacks;
  stats.cacheTileRepacks = counters.cacheTileRepacks;
  stats.cacheLocksBesideALock = counters.cacheLocksBesideALock;
  stats.cacheLocksContended = counters.cacheLocksContended;
  stats.cacheTilesPublished = counters.cacheTilesPublished;
  std::vector<std::uint64_t> passTicks;
  if (timestampPool_) {
    const bool builds = in_.acceleration->rebuiltEachFrame();
    const std::vector<std::uint64_t> ticks = readTimestamps(0, builds ? 5 : 2);
    stats.gpuMilliseconds = milliseconds(ticks[0], ticks[1], millisecondsPerTick_);
    if (builds) {
      stats.blasBuildMilliseconds += milliseconds(ticks[2], ticks[3], millisecondsPerTick_);
      stats.tlasBuildMilliseconds = milliseconds(ticks[3], ticks[4], millisecondsPerTick_);
    }
    if (tracerTimestamps_ > 0)
      passTicks = readTimestamps(kFirstTracerTimestamp, tracerTimestamps_);
  }
  in_.tracer->addFrameStats(trace, timestampPool_ ? &passTicks : nullptr, millisecondsPerTick_,
                            stats);
  stats.cullingHostMilliseconds += look.cullingHostMilliseconds;
  if (look.looks) {
    stats.looks = 1;
    stats.lookMilliseconds = look.lookMilliseconds;
    stats.lookRays = look.lookRays;
    stats.gpuMilliseconds += look.lookMilliseconds;
    stats.blasBuilds += look.blasBuilds;
    stats.blasUpdates += look.blasUpdates;
    stats.blasEvictions += look.blasEvictions;
    stats.blasBuildMilliseconds += look.blasBuildMilliseconds;
    stats.tlasBuildMilliseconds += look.tlasBuildMilliseconds;
    stats.blasBytes = std::max(stats.blasBytes, look.blasBytes);
    stats.asScratchBytes = std::max(stats.asScratchBytes, look.asScratchBytes);
  }
}

void FrameLoop::warmClocks() {
  const std::uint32_t milliseconds = in_.settings->clockWarmupMilliseconds;
  if (milliseconds == 0 || context_.info().type == VK_PHYSICAL_DEVICE_TYPE_CPU)
    return;
  if (!clockWarmup_)
    clockWarmup_.emplace(context_, in_.shaderCacheDirectory);
  clockWarmup_->run(std::chrono::milliseconds(milliseconds));
}

HdrImage FrameLoop::readImage() const {
  const RenderSettings& settings = *in_.settings;
  const std::uint64_t bytes = in_.plan->accumulationBytes;
  GpuBuffer readback = hostBuffer(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  context_.submitAndWait([&](VkCommandBuffer commands) {
    VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(commands, accumulation_.buffer(), readback.buffer(), 1, &copy);
  });
  HdrImage image;
  image.width = settings.width;
  image.height = settings.height;
  image.rgba.resize(std::size_t(settings.width) * settings.height * 4);
  readback.read(image.rgba.data(), bytes);
  return image;
}

void FrameLoop::run(RenderResult& result) {
  const RenderSettings& settings = *in_.settings;
  RenderAcceleration& accel = *in_.acceleration;
  Camera previousCamera;
  std::uint32_t sampleIndex = 0;
  previousRays_ = 0;
  const std::uint32_t first = settings.firstFrame, end = first + settings.frames;
  bool firstRendered = true;     // the render's first frame: submit sets up, its time is reported
  bool deferredCreated = false;  // the tracer's deferred pipelines, before the second frame
  warmClocks();
  for (std::uint32_t f = first; f < end; ++f) {
    if (settings.skipFrame && settings.skipFrame(f))
      continue;
    if (!firstRendered && !deferredCreated) {
      deferredCreated = true;
      // Before the second frame, whatever the first was rendered without for a quicker start.
      const auto start = std::chrono::steady_clock::now();
      result.stats.deferredPipelinesCreated = in_.tracer->createDeferredPipelines();
      result.stats.deferredPipelineMilliseconds =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      if (result.stats.deferredPipelinesCreated > 0)
        warmClocks();
    }
    const Camera& camera =
        settings.cameraPath.empty()
            ? in_.scene->camera
            : settings.cameraPath[std::min<std::size_t>(f, settings.cameraPath.size() - 1)];
    if (!firstRendered && (settings.eachFrameAlone || !sameCamera(camera, previousCamera)))
      sampleIndex = 0;
    previousCamera = camera;
    frame_.cameraForward.w = float(f) * settings.secondsPerFrame;
    setCamera(frame_, camera, settings.width, settings.height);
    frame_.image.z = f;
    frame_.culling.y = f / in_.culling->feedbackEvery;  // the counting frame's index
    frame_.environmentSize.z = sampleIndex;
    frame_.cache.y = f + 1u;  // the frame clock of §5.3.3 (0: never used)
    frameBuffer_.write(&frame_, sizeof frame_);
    FrameStats frameStats;
    frameStats.frame = f;
    // A look only where the frame starts the pixels' sums afresh (a new camera), so that the
    // probe's sample is replaced, not averaged in.
    FrameStats lookStats;
    if (sampleIndex == 0)
      look(f, camera, firstRendered, lookStats);
    accel.prepareFrame(camera, aspect_, f, frame_.cameraForward.w, previousRays_, frameStats);

    FrameTrace trace;
    trace.paths = settings.pathsPerPixel;
    trace.rays = settings.raysPerPath;
    trace.counts = accel.frameCounts();
    trace.counted = countedPaths(settings.pathsPerPixel, frame_.culling.z, frame_.culling.y);
    frameStats.feedbackFrame = trace.counts ? 1u : 0u;
    frameStats.traceDispatches = in_.tracer->dispatchCount(trace);
    const auto start = std::chrono::steady_clock::now();
    submit(firstRendered, trace);
    frameStats.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    readFrame(trace, lookStats, frameStats);
    if (firstRendered)
      result.stats.firstFrameMilliseconds = std::chrono::duration<double, std::milli>(
                                                std::chrono::steady_clock::now() - in_.renderStart)
                                                .count();
    accel.addFrame(frameStats, result.stats);
    result.stats.frames.push_back(frameStats);
    if (settings.onFrameImage && settings.frameImageWanted && settings.frameImageWanted(f))
      settings.onFrameImage(f, readImage());
    if (settings.onFrame)
      settings.onFrame(frameStats);
    ++sampleIndex;
    firstRendered = false;
    if (settings.continueAfterFrame && !settings.continueAfterFrame(frameStats))
      break;  // the image is the accumulation of the frames rendered so far
  }
  result.instanceStates = accel.instanceStates();
  result.instanceLods = accel.instanceLods();
  result.cullingView = accel.cullingView(previousCamera, in_.cullingViewSize);
  result.image = readImage();
}

}  // namespace memograph::runtime
