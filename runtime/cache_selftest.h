// The cache's concurrency self-test (thesis §5.3.4), built into the runtime so that it runs
// where the ordering matters: on a GPU (`memograph selftest`), not only on lavapipe, whose
// x86 threads are strongly ordered. A compute shader that includes the real texel_cache.glsl
// hammers a tiny cache (32 entries, D = 8, random eviction) with 64 keys whose values are a
// known function of the key and checks every hit's values. A torn read is a hit whose values
// belong to another key or to no completed write.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/vulkan_context.h"

namespace memograph::runtime {

// key: read key, values, key again (--cache-read-check key); counter: with the per-entry
// update counter (the default); image-key / image-counter: the values in an rgba32f storage
// image, as --tile-storage texture2d keeps tile texels; unprotected: no lock and no second
// look, which shows that the device and harness can tear at all.
enum class CacheStressMode { Key, Counter, ImageKey, ImageCounter, Unprotected };

const char* cacheStressModeName(CacheStressMode mode);

struct CacheStressResult {
  CacheStressMode mode = CacheStressMode::Key;
  std::uint32_t invocations = 0, iterations = 0;
  std::uint32_t hits = 0, torn = 0, writes = 0, misses = 0;
  std::uint32_t occupancy = 0;  // gpu::Counters::cacheOccupancy after the run
};

inline constexpr std::uint32_t kCacheStressEntries = 32;

// One dispatch of `invocations` (a multiple of 64) x `iterations` lookups.
CacheStressResult runCacheStress(const VulkanContext& context, CacheStressMode mode,
                                 std::uint32_t invocations, std::uint32_t iterations);

// The same harness for other checks of texel_cache.glsl's entry protocol: runs `body` (GLSL
// statements in main() of one invocation per `invocations`; the stubs of the stress shader
// are in scope, and `uint results[]` at binding kBindingRayCounter after gpu::Counters) over
// a cache of `entries` entries of `values` floats, with `defines` and the counter clock
// starting at `clockStart`. Returns the first `resultWords` words of `results`.
std::vector<std::uint32_t> runCacheProgram(const VulkanContext& context, const std::string& body,
                                           std::vector<std::string> defines, std::uint32_t entries,
                                           std::uint32_t invocations, std::uint64_t clockStart,
                                           std::uint32_t resultWords);

}  // namespace memograph::runtime
