// The frames of a render (Renderer::render's last stage): per frame the camera and frame
// constants, LiPaC's look where the culling wants one, the per-frame culling update, one
// submit (clears, builds, the architecture's trace through FrameTracer, read-backs) and the
// frame's statistics; at the end the accumulated image.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "runtime/accel/render_acceleration.h"
#include "runtime/memo/material_cache.h"
#include "runtime/renderer.h"
#include "runtime/scene/scene_resources.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/frame_tracer.h"
#include "runtime/trace/render_setup.h"
#include "runtime/trace/trace_descriptors.h"
#include "runtime/vk/clock_warmup.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// What the frames read; every pointer outlives the loop.
struct FrameLoopInputs {
  const Scene* scene = nullptr;
  const RenderSettings* settings = nullptr;
  const CullingOptions* culling = nullptr;
  const RenderPlan* plan = nullptr;
  const SceneResources* resources = nullptr;
  RenderAcceleration* acceleration = nullptr;
  const MaterialCache* cache = nullptr;
  FrameTracer* tracer = nullptr;  // its deferred pipelines are created before the 2nd frame
  std::filesystem::path shaderCacheDirectory;  // the clock warm-up's SPIR-V (none when empty)
  std::uint32_t cullingViewSize = 0;           // RendererOptions::debugCullingSize
  // When Renderer::render began: RenderStats::firstFrameMilliseconds counts from it.
  std::chrono::steady_clock::time_point renderStart = std::chrono::steady_clock::now();
};

class FrameLoop {
 public:
  // The per-render buffers, descriptor set and timestamp queries.
  FrameLoop(const VulkanContext& context, const FrameLoopInputs& inputs);

  // Renders settings.frames frames (fewer where continueAfterFrame says stop): appends each
  // frame's figures to result.stats, and sets the image and the culling's last states.
  void run(RenderResult& result);

 private:
  // One submit: clears (`firstFrame`: the cache and the persistent counters too), the
  // builds, the trace, the read-backs.
  void submit(bool firstFrame, const FrameTrace& trace) const;
  // LiPaC's look before frame `f`, where the culling wants one: fills `look`. `firstLook`:
  // before the render's first frame (it sets up, and traces every pixel).
  void look(std::uint32_t f, const Camera& camera, bool firstLook, FrameStats& look);
  // RenderSettings::clockWarmupMilliseconds on a GPU, after host work that left it idle.
  void warmClocks();
  // The figures of the frame just submitted (counters, timestamps), with its look's.
  void readFrame(const FrameTrace& trace, const FrameStats& look, FrameStats& stats);
  // The last submitted frame's timestamps first..first+count-1.
  std::vector<std::uint64_t> readTimestamps(std::uint32_t first, std::uint32_t count) const;
  gpu::Counters readCounters() const;
  HdrImage readImage() const;

  const VulkanContext& context_;
  FrameLoopInputs in_;
  float aspect_ = 1.0f;
  GpuBuffer frameBuffer_;
  GpuBuffer accumulation_;
  GpuBuffer rayCounter_;
  GpuBuffer rayReadback_;
  std::unique_ptr<TraceDescriptorSet> descriptors_;
  // Timestamps around each frame's trace (0, 1), then a dynamic set's animated BLASes and
  // TLAS (2-4), then the tracer's own from kFirstTracerTimestamp.
  VulkanHandle<VkQueryPool> timestampPool_;
  std::uint32_t timestampCount_ = 0;
  std::uint32_t tracerTimestamps_ = 0;
  double millisecondsPerTick_ = 0.0;
  gpu::FrameConstants frame_{};
  std::uint64_t previousRays_ = 0;
  std::optional<ClockWarmup> clockWarmup_;  // made at the first warmClocks() that runs
};

}  // namespace memograph::runtime
