#include "runtime/frame_counters.h"

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
  };
}

}  // namespace memograph::runtime
