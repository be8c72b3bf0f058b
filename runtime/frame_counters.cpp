#include "runtime/frame_counters.h"

namespace memograph::runtime {

std::vector<FrameCounter> frameCounters(const FrameStats& frame) {
  // New per-frame FrameStats fields (cache occupancy, tiles computed, ...) belong here too.
  return {
      {"rays", double(frame.rays)},
      {"cache_lookups", double(frame.cacheLookups)},
      {"cache_hits", double(frame.cacheHits)},
      {"cache_misses", double(frame.cacheMisses)},
  };
}

}  // namespace memograph::runtime
