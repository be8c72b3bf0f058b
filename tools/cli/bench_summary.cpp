// Only the bench command (which needs the runtime) uses these summaries.
#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "bench_summary.h"

#include <algorithm>
#include <sstream>

#include "runtime/trace/frame_counters.h"

namespace memograph::cli {

namespace {

double median(std::vector<double> values) {
  if (values.empty())
    return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

TimedFrameSummary summarizeTimedFrames(std::span<const runtime::FrameStats> frames) {
  TimedFrameSummary summary;
  std::vector<double> ms, mrays, hitRates, trace, shade, shadow, queue, bin, material, lookup,
      traced;
  std::vector<std::vector<double> > counters(runtime::frameCounters({}).size());
  for (const auto& frame : frames) {
    ms.push_back(frame.gpuMilliseconds);
    mrays.push_back(frame.gpuMilliseconds > 0 ? frame.rays / (frame.gpuMilliseconds * 1e3) : 0);
    hitRates.push_back(frame.cacheHitRate());
    trace.push_back(frame.wavefrontTraceMilliseconds);
    shade.push_back(frame.wavefrontShadeMilliseconds);
    shadow.push_back(frame.wavefrontShadowMilliseconds);
    queue.push_back(frame.wavefrontQueueMilliseconds);
    bin.push_back(frame.wavefrontBinMilliseconds);
    material.push_back(frame.wavefrontMaterialMilliseconds);
    lookup.push_back(frame.wavefrontLookupMilliseconds);
    traced.push_back(frame.wavefrontTracedInputsMilliseconds);
    summary.cacheLookups += frame.cacheLookups;
    summary.cacheHits += frame.cacheHits;
    const auto values = runtime::frameCounters(frame);
    for (std::size_t i = 0; i < values.size(); ++i)
      counters[i].push_back(values[i].value);
  }
  summary.medianMilliseconds = median(ms);
  summary.medianMraysPerSecond = median(mrays);
  summary.medianCacheHitRate = median(hitRates);
  summary.medianWavefrontTraceMilliseconds = median(std::move(trace));
  summary.medianWavefrontShadeMilliseconds = median(std::move(shade));
  summary.medianWavefrontShadowMilliseconds = median(std::move(shadow));
  summary.medianWavefrontQueueMilliseconds = median(std::move(queue));
  summary.medianWavefrontBinMilliseconds = median(std::move(bin));
  summary.medianWavefrontMaterialMilliseconds = median(std::move(material));
  summary.medianWavefrontLookupMilliseconds = median(std::move(lookup));
  summary.medianWavefrontTracedInputsMilliseconds = median(std::move(traced));
  summary.totalCacheHitRate =
      summary.cacheLookups ? double(summary.cacheHits) / double(summary.cacheLookups) : 0.0;
  const auto names = runtime::frameCounters({});
  for (std::size_t i = 0; i < counters.size(); ++i) {
    if (names[i].peak)
      summary.counterPeaks.push_back(
          counters[i].empty() ? 0.0 : *std::max_element(counters[i].begin(), counters[i].end()));
    summary.counterMedians.push_back(median(std::move(counters[i])));
  }
  return summary;
}

std::string benchSummaryCsvColumns() {
  std::string columns = "total_cache_hit_rate,cache_lookups_total,cache_hits_total";
  for (const auto& counter : runtime::frameCounters({}))
    columns += ",median_" + std::string(counter.name);
  for (const auto& counter : runtime::frameCounters({}))
    if (counter.peak)
      columns += ",peak_" + std::string(counter.name);
  return columns;
}

std::string benchSummaryCsvValues(const TimedFrameSummary& summary) {
  std::ostringstream out;
  out.precision(9);  // hit rates near 1: the thesis reports 99.999 %
  out << summary.totalCacheHitRate << ',' << summary.cacheLookups << ',' << summary.cacheHits;
  for (double value : summary.counterMedians)
    out << ',' << value;
  for (double value : summary.counterPeaks)
    out << ',' << value;
  return out.str();
}

std::string wavefrontPassCsvColumns() {
  return "median_wavefront_trace_gpu_ms,median_wavefront_shade_gpu_ms,"
         "median_wavefront_shadow_gpu_ms,median_wavefront_queue_gpu_ms,"
         "median_wavefront_bin_gpu_ms,median_wavefront_material_gpu_ms,"
         "median_wavefront_lookup_gpu_ms,median_wavefront_traced_inputs_gpu_ms,wavefront_paths,"
         "wavefront_chunks";
}

std::string wavefrontPassCsvValues(const TimedFrameSummary& summary,
                                   const runtime::RenderStats& stats) {
  if (stats.shading != "wavefront")
    return ",,,,,,,,,";
  std::ostringstream out;
  out << summary.medianWavefrontTraceMilliseconds << ',' << summary.medianWavefrontShadeMilliseconds
      << ',' << summary.medianWavefrontShadowMilliseconds << ','
      << summary.medianWavefrontQueueMilliseconds << ',' << summary.medianWavefrontBinMilliseconds
      << ',' << summary.medianWavefrontMaterialMilliseconds << ','
      << summary.medianWavefrontLookupMilliseconds << ','
      << summary.medianWavefrontTracedInputsMilliseconds << ',' << stats.wavefrontPathSlots << ','
      << stats.wavefrontChunks;
  return out.str();
}

}  // namespace memograph::cli

#endif  // MEMOGRAPH_HAVE_RUNTIME
