// The megakernel's frame (thesis §5.2): one kernel runs each path to its end, a frame's P
// paths in one or more dispatches (planPathDispatches), LiPaC's counting paths with the
// pipeline compiled with the feedback and the others, where there is one, without it; then
// the deferred tile fill's pass.
#pragma once

#include <cstdint>
#include <optional>

#include "runtime/trace/frame_tracer.h"
#include "runtime/trace/megakernel/trace_pipelines.h"

namespace memograph::runtime {

struct MegakernelSetup {
  TracePipelineSetup pipeline;  // the feedback's defines where LiPaC counts
  // LiPaC's frames that do not count, and the paths of a counting frame that do not, trace
  // with a second pipeline built with these defines (no MG_HIT_FEEDBACK; the same bindings,
  // so the same descriptor set).
  std::optional<std::vector<std::string>> quietDefines;
  // A counting frame traces its counted paths in dispatches of their own
  // (CullingOptions::feedbackPaths).
  bool splitCounting = false;
  std::uint32_t pathsPerDispatch = 0;  // 0: all P in one
  std::uint32_t width = 0, height = 0;
  std::uint32_t tileFillRows = 0;  // the deferred tile fill's rows (0: no fill pass)
};

class MegakernelTracer final : public FrameTracer {
 public:
  // Builds the pipeline and, with quietDefines, the quiet one at the same time on a second
  // thread (each a whole pipeline the driver compiles on the thread that creates it).
  MegakernelTracer(const VulkanContext& context, ShaderCompiler& compiler,
                   std::uint32_t textureCount, const MegakernelSetup& setup);

  const RayTracingStack& stack() const { return pipeline_->stack(); }

  VkDescriptorSetLayout descriptorSetLayout() const override {
    return pipeline_->descriptorSetLayout();
  }
  void addResources(TraceResources&) const override {}
  std::uint32_t timestampCount(std::uint32_t, std::uint32_t) const override { return 0; }
  std::uint32_t dispatchCount(const FrameTrace& trace) const override;
  void recordTrace(VkCommandBuffer commands, VkDescriptorSet set, const FrameTrace& trace,
                   VkQueryPool timestamps, std::uint32_t firstTimestamp) const override;
  void addFrameStats(const FrameTrace&, const std::vector<std::uint64_t>*, double,
                     FrameStats&) const override {}

 private:
  std::vector<PathDispatch> plan(const FrameTrace& trace) const;

  std::optional<TracePipeline> pipeline_;  // always built (the counting one with LiPaC)
  std::optional<TracePipeline> quietPipeline_;
  bool splitCounting_ = false;
  std::uint32_t pathsPerDispatch_ = 0;
  std::uint32_t width_ = 0, height_ = 0;
  std::uint32_t tileFillRows_ = 0;
};

}  // namespace memograph::runtime
