#include "runtime/trace/render_stats.h"

#include <algorithm>
#include <cstdio>

namespace memograph::runtime {

std::string RenderStats::cacheEntriesText() const {
  return std::to_string(cacheEntries) + " entries" +
         (cacheEntriesFitted ? " (the default, fitted to the device)" : "");
}

std::string pipelineCacheText(const RenderStats& stats) {
  std::string text = std::to_string(stats.pipelinesCreated) +
                     (stats.pipelinesCreated == 1 ? " pipeline, " : " pipelines, ");
  if (stats.pipelineCacheHitsReported)
    text += std::to_string(stats.pipelineCacheHits) + " from the pipeline cache";
  else
    text += "the driver does not say how many from the pipeline cache";
  // How many the driver compiled at a time, on average: the creation calls' summed time
  // over the stage's wall time.
  if (stats.pipelinesCreated > 0 && stats.pipelineCreateMilliseconds > 0.0) {
    char calls[96];
    std::snprintf(calls, sizeof calls, "; their creation calls %.0f ms summed, %.1f at a time",
                  stats.pipelineCreateCallMilliseconds,
                  stats.pipelineCreateCallMilliseconds / stats.pipelineCreateMilliseconds);
    text += calls;
  }
  if (stats.deferredPipelinesCreated > 0) {
    char deferred[128];
    std::snprintf(deferred, sizeof deferred,
                  "; before the second frame %u own material passes in %.0f ms",
                  stats.deferredPipelinesCreated, stats.deferredPipelineMilliseconds);
    text += deferred;
    if (stats.pipelineCacheHitsReported)
      text += " (" + std::to_string(stats.deferredPipelineCacheHits) + " from the pipeline cache)";
  }
  return text;
}

double RenderStats::medianGpuMilliseconds() const {
  if (frames.empty())
    return 0.0;
  std::vector<double> times;
  for (const auto& f : frames)
    times.push_back(f.gpuMilliseconds);
  std::sort(times.begin(), times.end());
  std::size_t n = times.size();
  return n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
}

std::uint64_t RenderStats::totalRays() const {
  std::uint64_t sum = 0;
  for (const auto& f : frames)
    sum += f.rays;
  return sum;
}

void writeStatsCsv(std::ostream& out, const RenderStats& s) {
  out << "frame,gpu_ms,wall_ms,rays,mrays_per_s,width,height,paths,rays_per_path,backend,"
         "device,blas_count,instances,blas_bytes,blas_bytes_uncompacted,tlas_bytes,"
         "scratch_bytes,as_build_ms,texture_bytes,materials,material_compile_ms,"
         "shader_compile_ms,shader_cache_hits,material_dispatch,pipeline_create_ms,"
         "cache,cache_eviction,cache_entries,cache_probe,cache_bytes,cache_lookups,cache_hits,"
         "cache_misses,cache_hit_rate,cache_read_check,cache_occupancy,cache_tiles_computed,"
         "cache_duplicate_tiles,cache_value_format,cache_clock,cache_snap_uv,"
         "cache_secondary_only,cache_clock_ticks,cache_tile,cache_tile_fallbacks,"
         "cache_tile_repacks,cache_locks_beside_a_lock,cache_locks_contended,culling,active_"
         "instances,omitted_instances,inactive_instances,"
         "waiting_instances,hitboxes,active_hitboxes,instance_state_changes,tlas_records,"
         "frame_blas_bytes,frame_tlas_bytes,frame_scratch_bytes,blas_builds,blas_updates,"
         "blas_evictions,"
         "blas_build_gpu_ms,tlas_build_gpu_ms,culling_host_ms,shading,"
         "wavefront_generate_gpu_ms,wavefront_trace_gpu_ms,wavefront_shade_gpu_ms,"
         "wavefront_queue_gpu_ms,wavefront_shadow_gpu_ms,wavefront_finish_gpu_ms,"
         "wavefront_bin_gpu_ms,wavefront_material_gpu_ms,wavefront_lookup_gpu_ms,"
         "wavefront_traced_inputs_gpu_ms,looks,look_gpu_ms,look_rays,feedback_frame,"
         "trace_dispatches\n";
  const auto& a = s.accelerationStructures;
  for (const auto& f : s.frames) {
    double mraysPerSecond = f.gpuMilliseconds > 0 ? f.rays / (f.gpuMilliseconds * 1e3) : 0.0;
    out << f.frame << ',' << f.gpuMilliseconds << ',' << f.wallMilliseconds << ',' << f.rays << ','
        << mraysPerSecond << ',' << s.width << ',' << s.height << ',' << s.pathsPerPixel << ','
        << s.raysPerPath << ',' << s.backend << ",\"" << s.device << "\"," << a.blasCount << ','
        << a.instanceCount << ',' << a.blasBytes << ',' << a.blasBytesBeforeCompaction << ','
        << a.tlasBytes << ',' << a.scratchBytes << ',' << a.buildMilliseconds << ','
        << s.textureBytes << ',' << s.materialCount << ',' << s.materialCompileMilliseconds << ','
        << s.shaderCompileMilliseconds << ',' << s.shaderCacheHits << ',' << s.materialDispatch
        << ',' << s.pipelineCreateMilliseconds << ',' << s.cache << ',' << s.cacheEviction << ','
        << s.cacheEntries << ',' << s.cacheProbe << ',' << s.cacheBytes << ',' << f.cacheLookups
        << ',' << f.cacheHits << ',' << f.cacheMisses << ',' << f.cacheHitRate() << ','
        << s.cacheReadCheck << ',' << f.cacheOccupancy << ',' << f.cacheTilesComputed << ','
        << f.cacheDuplicateTiles << ',' << s.cacheValueFormat << ',' << s.cacheClock << ','
        << int(s.cacheSnapUv) << ',' << int(s.cacheSecondaryOnly) << ',' << f.cacheClockTicks << ','
        << s.cacheTile << ',' << f.cacheTileFallbacks << ',' << f.cacheTileRepacks << ','
        << f.cacheLocksBesideALock << ',' << f.cacheLocksContended << ',' << s.culling << ','
        << f.activeInstances << ',' << f.omittedInstances << ',' << f.inactiveInstances << ','
        << f.waitingInstances << ',' << f.hitboxes << ',' << f.activeHitboxes << ','
        << f.instanceStateChanges << ',' << f.tlasRecords << ',' << f.blasBytes << ','
        << f.tlasBytes << ',' << f.asScratchBytes << ',' << f.blasBuilds << ',' << f.blasUpdates
        << ',' << f.blasEvictions << ',' << f.blasBuildMilliseconds << ','
        << f.tlasBuildMilliseconds << ',' << f.cullingHostMilliseconds << ',' << s.shading << ','
        << f.wavefrontGenerateMilliseconds << ',' << f.wavefrontTraceMilliseconds << ','
        << f.wavefrontShadeMilliseconds << ',' << f.wavefrontQueueMilliseconds << ','
        << f.wavefrontShadowMilliseconds << ',' << f.wavefrontFinishMilliseconds << ','
        << f.wavefrontBinMilliseconds << ',' << f.wavefrontMaterialMilliseconds << ','
        << f.wavefrontLookupMilliseconds << ',' << f.wavefrontTracedInputsMilliseconds << ','
        << f.looks << ',' << f.lookMilliseconds << ',' << f.lookRays << ',' << f.feedbackFrame
        << ',' << f.traceDispatches << '\n';
  }
}

}  // namespace memograph::runtime
