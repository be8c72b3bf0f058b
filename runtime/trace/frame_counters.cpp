#include "runtime/trace/frame_counters.h"

namespace memograph::runtime {

std::vector<FrameCounter> frameCounters(const FrameStats& frame) {
  // New per-frame FrameStats fields (cache occupancy, tiles computed, ...) belong here too.
  return {
      {"rays", double(frame.rays)},
      {"cache_lookups", double(frame.cacheLookups)},
      {"cache_hits", double(frame.cacheHits)},
      {"cache_misses", double(frame.cacheMisses)},
      {"tiles_computed", double(frame.cacheTilesComputed)},
      {"duplicate_tiles", double(frame.cacheDuplicateTiles)},
      {"tile_fallbacks", double(frame.cacheTileFallbacks)},
      {"tile_repacks", double(frame.cacheTileRepacks)},
      {"locks_beside_a_lock", double(frame.cacheLocksBesideALock)},
      {"locks_contended", double(frame.cacheLocksContended)},
      {"active_instances", double(frame.activeInstances)},
      {"omitted_instances", double(frame.omittedInstances)},
      {"active_hitboxes", double(frame.activeHitboxes)},
      {"tlas_records", double(frame.tlasRecords)},
      {"as_bytes", double(frame.blasBytes + frame.tlasBytes), true},
      {"blas_builds", double(frame.blasBuilds)},
      {"blas_updates", double(frame.blasUpdates)},
      {"blas_evictions", double(frame.blasEvictions)},
      {"blas_build_gpu_ms", frame.blasBuildMilliseconds},
      {"tlas_build_gpu_ms", frame.tlasBuildMilliseconds},
      {"culling_host_ms", frame.cullingHostMilliseconds},
      {"trace_dispatches", double(frame.traceDispatches)},
  };
}

}  // namespace memograph::runtime
