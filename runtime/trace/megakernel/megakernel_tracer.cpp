#include "runtime/trace/megakernel/megakernel_tracer.h"

#include <algorithm>
#include <future>

namespace memograph::runtime {

namespace {

TracePipelineSetup quietSetup(TracePipelineSetup setup, const std::vector<std::string>& defines) {
  setup.defines = defines;
  return setup;
}

// Orders a dispatch's shader writes before the next pass's reads and writes.
void shaderBarrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace

MegakernelTracer::MegakernelTracer(const VulkanContext& context, ShaderCompiler& compiler,
                                   std::uint32_t textureCount, const MegakernelSetup& setup)
    : splitCounting_(setup.splitCounting),
      pathsPerDispatch_(setup.pathsPerDispatch),
      width_(setup.width),
      height_(setup.height),
      tileFillRows_(setup.tileFillRows) {
  if (!setup.quietDefines) {
    pipeline_.emplace(context, compiler, textureCount, setup.pipeline);
    return;
  }
  // Each with a compiler of its own (a compiler's statistics are not shared); their compile
  // times overlap, so the longer one is what the pair cost.
  ShaderCompiler countingCompiler = compiler.fresh();
  ShaderCompiler quietCompiler = compiler.fresh();
  const TracePipelineSetup quiet = quietSetup(setup.pipeline, *setup.quietDefines);
  // Declared after what it uses: if the counting pipeline throws, leaving the scope waits
  // for the quiet one first.
  std::future<void> quietBuilt = std::async(std::launch::async, [&] {
    quietPipeline_.emplace(context, quietCompiler, textureCount, quiet);
  });
  pipeline_.emplace(context, countingCompiler, textureCount, setup.pipeline);
  quietBuilt.get();
  compiler.addConcurrentStats({countingCompiler.stats(), quietCompiler.stats()});
}

std::vector<PathDispatch> MegakernelTracer::plan(const FrameTrace& trace) const {
  // A look's paths all count, in one run: it is one probe trace.
  return planPathDispatches(trace.paths, pathsPerDispatch_, trace.counts,
                            splitCounting_ && !trace.look, trace.counted);
}

std::uint32_t MegakernelTracer::dispatchCount(const FrameTrace& trace) const {
  return static_cast<std::uint32_t>(plan(trace).size());
}

void MegakernelTracer::recordTrace(VkCommandBuffer commands, VkDescriptorSet set,
                                   const FrameTrace& trace, VkQueryPool, std::uint32_t) const {
  // A sparse look's image is smaller than the frame's: a launch past it would trace rays
  // outside the frustum (the pipeline backend's raygen takes every launch as a pixel).
  const std::uint32_t width = trace.width > 0 ? std::min(trace.width, width_) : width_;
  const std::uint32_t height = trace.height > 0 ? std::min(trace.height, height_) : height_;
  for (const PathDispatch& d : plan(trace)) {
    // A later dispatch adds its share to what the earlier ones wrote (renderPixel).
    if (d.adds)
      shaderBarrier(commands);
    const TracePipeline& traced = quietPipeline_ && !d.feedback ? *quietPipeline_ : *pipeline_;
    traced.record(commands, set, width, height, d.push());
  }
  if (tileFillRows_ > 0) {
    // The deferred tile fill computes the tiles the trace queued (its stores, queue and
    // locks ordered after the trace's); the frame's time includes it.
    shaderBarrier(commands);
    pipeline_->recordTileFill(commands, set, tileFillRows_);
  }
}

}  // namespace memograph::runtime
