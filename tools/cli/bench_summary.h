// What `memograph bench` reports for the timed frames of one run: medians (robust to the
// odd slow frame) and, for the cache, the total hit rate (hits over lookups summed over the
// timed frames), which weighs each frame by its lookups as the thesis's tables do.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "runtime/trace/render_stats.h"

namespace memograph::cli {

struct TimedFrameSummary {
  double medianMilliseconds = 0.0;
  double medianMraysPerSecond = 0.0;
  double medianCacheHitRate = 0.0;
  double totalCacheHitRate = 0.0;  // 0 without lookups
  std::uint64_t cacheLookups = 0;  // summed over the timed frames
  std::uint64_t cacheHits = 0;
  // Median of each of runtime::frameCounters(), in its order.
  std::vector<double> counterMedians;
  // The largest value of each counter marked `peak`, in its order.
  std::vector<double> counterPeaks;
  // The wavefront path tracer's passes (--shading wavefront): median GPU time of each kind,
  // summed over a frame's rounds and bounces.
  double medianWavefrontTraceMilliseconds = 0.0;
  double medianWavefrontShadeMilliseconds = 0.0;
  double medianWavefrontShadowMilliseconds = 0.0;
  double medianWavefrontQueueMilliseconds = 0.0;
  double medianWavefrontBinMilliseconds = 0.0;
  double medianWavefrontMaterialMilliseconds = 0.0;
  double medianWavefrontLookupMilliseconds = 0.0;
  double medianWavefrontTracedInputsMilliseconds = 0.0;
};

TimedFrameSummary summarizeTimedFrames(std::span<const runtime::FrameStats> frames);

// The bench CSV's trailing columns (after the fixed ones of bench_command.cpp) and their
// values, so the per-frame counters' names come from one place.
std::string benchSummaryCsvColumns();
std::string benchSummaryCsvValues(const TimedFrameSummary& summary);

// The wavefront passes' columns (median_wavefront_{trace,shade,shadow,queue,bin,material,
// lookup}_gpu_ms, then wavefront_paths and wavefront_chunks: paths in flight, chunks a round)
// and
// their values: empty for the megakernel, which has no passes.
std::string wavefrontPassCsvColumns();
std::string wavefrontPassCsvValues(const TimedFrameSummary& summary,
                                   const runtime::RenderStats& stats);

}  // namespace memograph::cli
