// The material graph cache's options (thesis §4, §5.3) and what they turn into: the texel
// cache's shader defines and its entry size. Shared by the renderer, the CLI and the tests.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace memograph::runtime {

// Material graph memoization (thesis §4, §5.3-5.4). Texel: one hash table of texels, keyed
// by material, mip level and texel (eq. 5.1-5.10), linear probing over `probe` entries.
// Tile: entries are tiles of texels, computed by a whole subgroup on a miss (§5.4.3).
enum class CacheMode { None, Texel, Tile };
// How a tile is sampled (§4.6, eq. 5.12-5.15): its nearest texel, or bilinearly from tiles
// that overlap by one texel.
enum class TileFilter { Nearest, Bilinear };
// Where a tile's texels live (§5.4.1). Values are the shader's kTileStorage*.
enum class TileStorage { Entry = 0, Buffer = 1, Texture2D = 2, Texture3D = 3 };
// What a miss evicts when its probe range is full (§4.5): none (insert only into empty
// entries), the least recently used or least recently written entry by a clock (§5.3.3),
// or a pseudo-random entry. Values are the shader's kCacheEviction*.
enum class CacheEviction { None = 0, Lru = 1, Lrw = 2, Random = 3 };
// How an entry stores the graph's outputs (§5.3.1): 32-bit floats, or 16-bit floats two to
// a uint (half the value words; values clamped to ±65504).
enum class CacheValueFormat { Fp32, Fp16 };
// The lru/lrw time of §5.3.3: the host's frame counter, or a 64-bit GPU atomic counter
// bumped by every stamping access (needs shaderBufferInt64Atomics).
enum class CacheClock { Frame, Counter };
// Who computes a missing tile (§5.4.3). Subgroup: the thesis's eight steps, the requesting
// subgroup computes it at once, one texel per lane. Deferred: the first request of a frame
// locks an entry and queues the tile, evaluates its own hit directly (as a texel-cache miss
// does), and a second pass after the frame's trace computes every queued tile, one
// invocation per texel, and publishes it for the next frame. The second pass needs no lane
// to survive a callable in place, which NVIDIA's raygen does not guarantee
// (docs/design/memoization.md, "The tile cache").
enum class TileFill { Subgroup, Deferred };
// How the texel cache reads its key space (docs/design/memoization.md, "Filtering"): the
// nearest entry of the nearest level; the trilinear blend of the entries around the hit at
// the two levels around its continuous level (thesis §7; 8 lookups for uv keys, 16 for voxel
// keys); or one of those entries picked per sample with its weight as probability (seed 002
// §3.2), one lookup, the trilinear value in expectation. Values are the shader's
// kCacheFilter*.
enum class CacheFilter { Nearest = 0, Trilinear = 1, Stochastic = 2 };
// The key domains the cache takes (docs/design/memoization.md, "Keys of the cut"), as bits: a
// material whose key is in another domain runs uncached. uv holds the whole uv-only materials
// too. Comparing the cache with one domain at a time shows what each domain serves.
inline constexpr std::uint32_t kCacheKeyUv = 1u;
inline constexpr std::uint32_t kCacheKeyObject = 2u;
inline constexpr std::uint32_t kCacheKeyWorld = 4u;
inline constexpr std::uint32_t kCacheKeysAll = kCacheKeyUv | kCacheKeyObject | kCacheKeyWorld;

const char* cacheModeName(CacheMode mode);
const char* cacheEvictionName(CacheEviction eviction);
const char* cacheValueFormatName(CacheValueFormat format);
const char* cacheClockName(CacheClock clock);
const char* tileFilterName(TileFilter filter);
const char* tileStorageName(TileStorage storage);
const char* tileFillName(TileFill fill);
const char* cacheFilterName(CacheFilter filter);
// "uv,object,world" (the domains in that order, comma-separated), or "all".
std::string cacheKeyDomainsName(std::uint32_t domains);
// Parse "none"/"texel", "none"/"lru"/"lrw"/"random", "fp32"/"fp16" and "frame"/"counter";
// throw std::invalid_argument naming the choices.
CacheMode parseCacheMode(const std::string& text);
CacheEviction parseCacheEviction(const std::string& text);
CacheValueFormat parseCacheValueFormat(const std::string& text);
CacheClock parseCacheClock(const std::string& text);
// "nearest"/"bilinear" and "entry"/"buffer"/"texture2d"/"texture3d", likewise.
TileFilter parseTileFilter(const std::string& text);
TileStorage parseTileStorage(const std::string& text);
// "subgroup"/"deferred".
TileFill parseTileFill(const std::string& text);
// "nearest"/"trilinear"/"stochastic".
CacheFilter parseCacheFilter(const std::string& text);
// "all", or a comma-separated list of uv, object and world (each at most once).
std::uint32_t parseCacheKeyDomains(const std::string& text);

// The entry count S when CacheOptions::entries is unset: the best rows measured on the GPU
// machine, fitted to the device (material_cache.cpp: halved while over the storage-buffer
// range or a quarter of the device-local memory). kDefaultTexelCacheEntries: 2^24 texels
// (docs/results.md, Table 6.1; 3x faster there than 2^20 texels). kDefaultCacheEntries:
// 2^21 tiles of 4x4. Table 6.1's megakernel sweep went up to 2^20 tiles, each size faster
// than the one below; in the wavefront, the GPU's default (H200, the classroom's whole path,
// 1080p, P = 6, L = 4), 2^20, 2^21 and 2^22 tiles took 59.9, 59.8 and 59.6 ms with median
// hit rates of 99.894, 99.937 and 99.955 %: 2^21 is past the 99.9 % at half 2^22's memory
// (967 against 1,931 MB). docs/results.md, "The whole camera path".
inline constexpr std::uint32_t kDefaultCacheEntries = 1u << 21;
inline constexpr std::uint32_t kDefaultTexelCacheEntries = 1u << 24;

struct CacheOptions {
  CacheMode mode = CacheMode::None;
  // S; must exceed `probe`. Unset: defaultCacheEntries(mode), halved while a buffer holding
  // the entries would exceed the device's storage-buffer range (the most one binding may
  // address: 128 MiB on lavapipe, where 2^20 tiles of 4x2 texels do not fit) or a quarter of
  // its device-local memory; a given count that does not fit is refused.
  std::optional<std::uint32_t> entries;
  std::uint32_t probe = 8;  // D, 1..16 (gpu::kCacheMaxProbe)
  float mipBias = 0.0f;     // eq. 5.5; positive: finer texels
  CacheEviction eviction = CacheEviction::Lru;
  // §5.3.4: true adds a per-entry update counter that closes the A-B-A race (one more uint
  // per entry and an atomic per write); false checks a read by reading the key again (the
  // thesis's choice). The default is the counter: on an H200 (classroom, 1080p, 300 frames)
  // it cost nothing measurable (texel 123.8 vs 125.1 ms, tile 147.3 vs 146.3 ms).
  bool updateCounter = true;
  CacheValueFormat valueFormat = CacheValueFormat::Fp32;
  // Unset: for the texel cache under lru the frame clock; otherwise the counter clock where
  // the device has 64-bit buffer atomics, else the frame clock (resolveCacheOptions). Measured
  // on an H200 (classroom, 1080p, P = 6, L = 4, lru): texel at the default 2^24 entries, the
  // wavefront, 65.0 ms with the frame clock against 69.6 ms with the counter at the same hit
  // rate (99.689 against 99.690 %), and in the megakernel at 2^23 124.0 against 127.8 ms
  // (99.599 against 99.595 %); only at 2^21 texels was the counter ahead (200.4 against
  // 205.1 ms). Tiles need the counter: at 2^17 tiles the frame clock's lru collapsed (471.9
  // against 293.6 ms, 91.8 against 95.2 %); so does lrw, whose frame clock cannot order the
  // writes of one frame (texel lrw at 2^21: 416.8 ms and 90.0 % with the frame clock, 198.3 ms
  // and 96.3 % with the counter; all figures from the re-sweep's tables except the wavefront's).
  std::optional<CacheClock> clock;
  // Counter clock: the entry keeps counter bits clockShift..clockShift+31. Unset: per policy
  // (cacheClockShift): lru about 2^10 ages a frame (16 at 1080p, P = 6, L = 4: §5.3.3's
  // "bits 16 to 48"), where every read and write ticks; lrw 0, since only writes tick (at 16 one
  // age spanned about 65,000 writes and lrw-counter acted like lrw-frame). Ages are compared modulo
  // 2^32, so a wrap of the kept bits is harmless. Tiny images (tests) need 0, or every stamp of a
  // short run is 0.
  std::optional<std::uint32_t> clockShift;
  // §6.1: evaluate a miss at its texel's centre, so an entry holds the texel's value.
  bool snapUv = false;
  // The texel cache's filter (docs/design/memoization.md, "Filtering"); a filtered miss is
  // always evaluated at its entry's centre, with or without snapUv. The wavefront reads
  // filtered entries in its material passes.
  CacheFilter filter = CacheFilter::Nearest;
  // kCacheKey* bits: the key domains cached; the others' materials run uncached.
  std::uint32_t keyDomains = kCacheKeysAll;
  // §6.1, Fig. 6.6: primary hits evaluate their graph directly; only bounces >= 1 cache.
  bool secondaryOnly = false;
  // Texel cache, nearest filter: frames a key lives before its cell is keyed and filled anew at
  // another point of the cell, each key at its own phase (texel_cache.glsl cacheKeyOfHashes);
  // 0: never, an entry keeps its cell's centre value (the snapped or cut evaluation) or its
  // first hit's for as long as it stays. Unset: the defaults of cacheRefreshOf.
  std::optional<std::uint32_t> refreshFrames;
  // Tile cache (§5.4): texels stored per tile (W x H <= the device's subgroup size; the
  // thesis's 4 x 4 needs 16 lanes, lavapipe has 8), the filter, the storage and §5.4.4's
  // grouping of missing tiles by material. `entries` counts tiles.
  std::uint32_t tileWidth = 4;
  std::uint32_t tileHeight = 4;
  TileFilter tileFilter = TileFilter::Nearest;
  TileStorage tileStorage = TileStorage::Entry;
  bool groupByMaterial = false;
  // Unset: the subgroup fill in the megakernel; the wavefront always queues (render_setup.cpp),
  // and Shading::Auto takes an explicit Subgroup as a reason for the megakernel.
  std::optional<TileFill> tileFill;
  // Deferred fill: tiles queued per frame at most; a request past it evaluates its hit
  // and queues nothing (counted as a fallback). 32 bytes each.
  std::uint32_t tileQueue = 1u << 16;
  // Test hook (no CLI flag): half the lanes of every subgroup skip the tile cache, so the
  // partial subgroups NVIDIA's raygen has can be exercised on lavapipe.
  bool testPartialSubgroups = false;
  // Test hook (no CLI flag): after each texel evaluation half the lanes look as if they
  // came back from another subgroup (NVIDIA's raygen regroups lanes across callables), so
  // the repack check and its give-up path run on lavapipe's query backend.
  bool testRepacks = false;
  // With testRepacks: the percentage of the subgroup fill's iterations the hook fires in
  // (100: every one), chosen by a hash of the subgroup, its first tile and the frame. The
  // H200 gives up about 60 % of the tiles it starts on the classroom (callable repacks); this
  // lets lavapipe run the eviction policies under such a rate (the CLI's test-only
  // environment variable MEMOGRAPH_TEST_TILE_GIVE_UP).
  std::uint32_t testRepackPercent = 100;
};

// Throws std::invalid_argument naming the option (CLI spelling) when out of range.
void validateCacheOptions(const CacheOptions& options);

// The refresh of object- and world-space keys when CacheOptions::refreshFrames is unset. A
// voxel's entry holds one point of a cell that, under a bounce's wide cone, spans much of the
// material's variation, and that point biases a converged picture: on the Blender material
// scene (H100, 1536 samples a pixel) the still camera's 8x8-block error is 1.12x the
// seed-to-seed noise without refresh and 0.77x with this default, for 7 % of the frame
// (docs/design/memoization.md, "Refresh"). A uv texel follows its texture's pixel footprint,
// and the classroom's and the landscape's uv keys are not refreshed by default.
constexpr std::uint32_t kDefaultVoxelRefreshFrames = 16;

// Frames a key lives (0: never refreshed) for the texel cache's uv keys (whole uv-only
// graphs, uv cuts) and its voxel keys (object- and world-space cuts): a given refreshFrames
// for both, else 0 and kDefaultVoxelRefreshFrames; 0 for both with the tile cache or a
// filter (they evaluate entries at their cells' centres).
struct CacheRefresh {
  std::uint32_t uv = 0;
  std::uint32_t voxel = 0;
};
CacheRefresh cacheRefreshOf(const CacheOptions& options);
// How `refresh` renews keys, for the printed configuration: "keys refreshed never", "keys
// refreshed every N frames", or each kind's period ("keys refreshed: uv never, voxel every N
// frames").
std::string cacheRefreshText(const CacheRefresh& refresh);

// S when CacheOptions::entries is unset, before fitting: kDefaultTexelCacheEntries texels or
// kDefaultCacheEntries tiles.
std::uint32_t defaultCacheEntries(CacheMode mode);
// The clock an unset CacheOptions::clock means on a device with or without 64-bit buffer
// atomics, and the shift an unset clockShift means for the eviction policy.
// `lookupsPerFrame` (pixels x paths x rays, 0: unknown) sizes lru's shift: about 2^10
// ages a frame, round(log2(lookups)) - 10 (16 at 1080p, P = 6, L = 4: §5.3.3's bits 16..47;
// 0 for the tiny images of tests, whose counter never reaches 2^16); 16 when unknown.
CacheClock cacheClockOf(const CacheOptions& options, bool bufferInt64Atomics = true);
std::uint32_t cacheClockShift(const CacheOptions& options, std::uint64_t lookupsPerFrame = 0);
// `options` with clock and clockShift set to what they mean on the device and image.
CacheOptions resolveCacheOptions(CacheOptions options, bool bufferInt64Atomics,
                                 std::uint64_t lookupsPerFrame = 0);

// uints per texel's values and per entry (header — with the subgroup tile fill's texel
// count — + the values stored in the entry: one texel's for the texel cache, a tile's with
// kTileStorageEntry, none for other tile storages) for `valueCount` floats per texel.
std::uint32_t cacheValueWords(const CacheOptions& options, std::uint32_t valueCount);
std::uint32_t cacheEntryWords(const CacheOptions& options, std::uint32_t valueCount);

// Texels per entry: 1, or W x H for the tile cache.
std::uint32_t cacheTexelsPerEntry(const CacheOptions& options);

// The defines texel_cache.glsl, tile_cache.glsl and path_tracer.glsl read (none for
// CacheMode::None).
std::vector<std::string> cacheShaderDefines(const CacheOptions& options, std::uint32_t valueCount);

}  // namespace memograph::runtime
