// What one frame's trace records, whichever architecture runs it: the megakernel
// (MegakernelTracer, thesis §5.2) or the wavefront (WavefrontPathTracer). FrameLoop drives
// either the same way: it clears, builds, traces through this interface and reads back.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/trace/megakernel/path_dispatches.h"
#include "runtime/trace/render_stats.h"
#include "runtime/trace/trace_descriptors.h"

namespace memograph::runtime {

// One trace of the image: a frame's, or LiPaC's look before it.
struct FrameTrace {
  std::uint32_t paths = 1;  // P: paths per pixel
  std::uint32_t rays = 1;   // L: rays per path
  bool counts = false;      // LiPaC counts its hits (the feedback's pipeline)
  bool look = false;        // LiPaC's look: one probe trace, its paths counted together
  CountedPaths counted;     // the counting paths of a counting frame
  // The trace's image (FrameConstants::image.xy): 0 x 0, the frame's; a sparse look traces
  // one path per block of pixels, so its image is smaller.
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

class FrameTracer {
 public:
  virtual ~FrameTracer() = default;

  virtual VkDescriptorSetLayout descriptorSetLayout() const = 0;
  // Adds the architecture's own buffers to the trace's descriptor set.
  virtual void addResources(TraceResources& resources) const = 0;
  // Timestamps recordTrace writes from its first query on, for `paths` P and `rays` L.
  virtual std::uint32_t timestampCount(std::uint32_t paths, std::uint32_t rays) const = 0;
  // The trace's dispatches, for FrameStats::traceDispatches (0: not the megakernel's kind).
  virtual std::uint32_t dispatchCount(const FrameTrace& trace) const = 0;
  // Records the trace between the frame's TLAS build and its read-backs, with the barriers
  // its own passes need; `timestamps` VK_NULL_HANDLE: none.
  virtual void recordTrace(VkCommandBuffer commands, VkDescriptorSet set, const FrameTrace& trace,
                           VkQueryPool timestamps, std::uint32_t firstTimestamp) const = 0;
  // After the frame completed: the architecture's own figures; `passTicks` the timestamps
  // recordTrace wrote (null without timestamps).
  virtual void addFrameStats(const FrameTrace& trace, const std::vector<std::uint64_t>* passTicks,
                             double millisecondsPerTick, FrameStats& stats) const = 0;
  // Pipelines the set-up deferred past the first frame, created before the second (the frame
  // loop calls it once there): the wavefront's graphs' own material passes. Returns how many.
  virtual std::uint32_t createDeferredPipelines() { return 0; }
};

}  // namespace memograph::runtime
