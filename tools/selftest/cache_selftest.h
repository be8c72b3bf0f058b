// The cache's concurrency self-test (thesis §5.3.4), built into the runtime so that it runs
// where the ordering matters: on a GPU (`memograph selftest`), not only on lavapipe, whose
// x86 threads are strongly ordered. A compute shader that includes the real texel_cache.glsl
// hammers a tiny cache (32 entries, D = 8, random eviction) with 64 keys whose values are a
// known function of the key and checks every hit's values. A torn read is a hit whose values
// belong to another key or to no completed write. The tile cache's subgroup fill (§5.4.3,
// tile_cache.glsl) gets the same treatment with whole tiles (runTileFillStress).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/memo/cache_options.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

// key: read key, values, key again (the thesis's §5.3.4 read check, which tears by the
// A-B-A race); counter: with the per-entry update counter (the renderer's protocol); image-key /
// image-counter: the values in an rgba32f storage image, as --tile-storage texture2d keeps tile
// texels; unprotected: no lock and no second look, which shows that the device and harness can tear
// at all.
enum class CacheStressMode { Key, Counter, ImageKey, ImageCounter, Unprotected };

const char* cacheStressModeName(CacheStressMode mode);

// Whether a torn read in `mode` is a defect: true for the renderer's protocol (the update
// counter, with values in a buffer or an image), which must never tear. The key re-read
// check tears by design (two writes that restore the key while a reader reads, the A-B-A
// race of §5.3.4 that the counter closes) and no protection tears at once; both are run as
// demonstrations that the harness sees tears, so their counts are reported, never failed.
bool cacheStressModeMustNotTear(CacheStressMode mode);

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

// The SPIR-V of `mode`'s stress program, as runCacheStress compiles it: what a test reads to
// check that the protocol is written for the Vulkan memory model.
std::vector<std::uint32_t> cacheStressSpirv(CacheStressMode mode);

// The tile cache's subgroup fill (tile_cache.glsl tileComputeMissing, thesis §5.4.3) under
// the same contention: 64 tiles of one material, whose texels are a known function of their
// uv, on 32 entries (D = 8, random eviction), through the real tile_cache.glsl. Each
// iteration every computing lane reads its tile whole (all W*H texels between the entry
// protocol's checks) and the subgroup computes the tiles its lanes missed. A torn read is a
// hit with a texel that is not the tile's (stored for another tile, or not yet visible: what
// a publication before the last texel's store would give). The repack hook gives
// computations up from pass 0, 1, ... or never, so tiles are given up with part of their
// texels stored.
enum class TileFillLanes {
  All,        // every lane computes; tiles of a quarter of the subgroup, 4 an iteration
  Quarter,    // a quarter of the lanes; tiles of the subgroup's size, 4 passes each
  AllButOne,  // all lanes but the last; tiles of the subgroup's size, 2 passes, the second
              // of one texel (so a count that completes early leaves that texel's add behind)
};

struct TileFillStressOptions {
  TileStorage storage = TileStorage::Entry;
  TileFillLanes lanes = TileFillLanes::All;
  bool repacks = false;
  bool fp16 = false;
  bool updateCounter = true;  // the renderer's protocol; false: the key read check
};

struct TileFillStressResult {
  TileFillStressOptions options;
  std::uint32_t invocations = 0, iterations = 0;
  std::uint32_t tileWidth = 0, tileHeight = 0, passes = 0;  // passes a tile takes
  std::uint32_t computingLanes = 0;  // of a subgroup of DeviceInfo::subgroupSize lanes
  std::uint32_t hits = 0, torn = 0, misses = 0;
  std::uint32_t served = 0, wrongServed = 0;  // lanes the exchange served, with a wrong texel
  // Tiles locked and computed, published by their last texel, given back empty; duplicates
  // (a tile published again while the tile log had it), repack lane-events, fallbacks.
  std::uint32_t tilesComputed = 0, tilesPublished = 0, tilesGivenUp = 0, duplicateTiles = 0;
  std::uint32_t repacks = 0, fallbacks = 0;
  // After the run: entries still locked, entries whose texel count is not back to 0,
  // entries holding a key, and gpu::Counters::cacheOccupancy.
  std::uint32_t entriesLocked = 0, countsLeft = 0, entriesFilled = 0, occupancy = 0;
  // What is wrong, empty when nothing: a torn or wrongly served texel, an entry left locked
  // or with a count, a computed tile neither published nor given up (or both), an occupancy
  // other than the entries in use, or a run that published nothing (or, with the hook, gave
  // nothing up).
  std::string failure() const;
};

std::string tileFillStressName(const TileFillStressOptions& options);

// One dispatch of `invocations` (a multiple of 64) x `iterations` tile lookups. Throws
// std::invalid_argument when the device lacks the subgroup operations in compute shaders.
TileFillStressResult runTileFillStress(const VulkanContext& context,
                                       const TileFillStressOptions& options,
                                       std::uint32_t invocations, std::uint32_t iterations);

// The configurations `memograph selftest` runs: every storage layout, several tiles an
// iteration and several passes a tile, given-up tiles, fp16.
std::vector<TileFillStressOptions> tileFillStressConfigurations();

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
