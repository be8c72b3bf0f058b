#include "runtime/memo/cache_options.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

static_assert(static_cast<std::uint32_t>(CacheEviction::Lru) == gpu::kCacheEvictionLru &&
              static_cast<std::uint32_t>(CacheEviction::Lrw) == gpu::kCacheEvictionLrw &&
              static_cast<std::uint32_t>(CacheEviction::Random) == gpu::kCacheEvictionRandom);
static_assert(static_cast<std::uint32_t>(CacheFilter::Nearest) == gpu::kCacheFilterNearest &&
              static_cast<std::uint32_t>(CacheFilter::Trilinear) == gpu::kCacheFilterTrilinear &&
              static_cast<std::uint32_t>(CacheFilter::Stochastic) == gpu::kCacheFilterStochastic);

const char* cacheModeName(CacheMode mode) {
  switch (mode) {
    case CacheMode::None:
      return "none";
    case CacheMode::Texel:
      return "texel";
    case CacheMode::Tile:
      return "tile";
  }
  return "none";
}

const char* cacheEvictionName(CacheEviction eviction) {
  switch (eviction) {
    case CacheEviction::None:
      return "none";
    case CacheEviction::Lru:
      return "lru";
    case CacheEviction::Lrw:
      return "lrw";
    case CacheEviction::Random:
      return "random";
  }
  return "none";
}

const char* cacheValueFormatName(CacheValueFormat format) {
  return format == CacheValueFormat::Fp16 ? "fp16" : "fp32";
}

const char* cacheClockName(CacheClock clock) {
  return clock == CacheClock::Counter ? "counter" : "frame";
}

const char* cacheFilterName(CacheFilter filter) {
  switch (filter) {
    case CacheFilter::Nearest:
      return "nearest";
    case CacheFilter::Trilinear:
      return "trilinear";
    case CacheFilter::Stochastic:
      return "stochastic";
  }
  return "nearest";
}

CacheFilter parseCacheFilter(const std::string& text) {
  if (text == "nearest")
    return CacheFilter::Nearest;
  if (text == "trilinear")
    return CacheFilter::Trilinear;
  if (text == "stochastic")
    return CacheFilter::Stochastic;
  throw std::invalid_argument("unknown --cache-filter '" + text +
                              "' (choose nearest, trilinear or stochastic)");
}

std::string cacheKeyDomainsName(std::uint32_t domains) {
  if ((domains & kCacheKeysAll) == kCacheKeysAll)
    return "all";
  std::string name;
  for (const auto& [bit, word] :
       {std::pair{kCacheKeyUv, "uv"}, std::pair{kCacheKeyObject, "object"},
        std::pair{kCacheKeyWorld, "world"}})
    if (domains & bit) {
      if (!name.empty())
        name += ',';
      name += word;
    }
  return name;
}

std::uint32_t parseCacheKeyDomains(const std::string& text) {
  if (text == "all")
    return kCacheKeysAll;
  std::uint32_t domains = 0;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string word = text.substr(begin, end - begin);
    const std::uint32_t bit = word == "uv"       ? kCacheKeyUv
                              : word == "object" ? kCacheKeyObject
                              : word == "world"  ? kCacheKeyWorld
                                                 : 0u;
    if (bit == 0u || (domains & bit))
      throw std::invalid_argument(
          "--cache-keys takes all, or uv, object and world separated by "
          "commas, each once; not '" +
          text + "'");
    domains |= bit;
    begin = end + 1;
  }
  return domains;
}

CacheMode parseCacheMode(const std::string& text) {
  if (text == "none")
    return CacheMode::None;
  if (text == "texel")
    return CacheMode::Texel;
  if (text == "tile")
    return CacheMode::Tile;
  throw std::invalid_argument("unknown cache '" + text + "' (choose none, texel or tile)");
}

CacheEviction parseCacheEviction(const std::string& text) {
  if (text == "none")
    return CacheEviction::None;
  if (text == "lru")
    return CacheEviction::Lru;
  if (text == "lrw")
    return CacheEviction::Lrw;
  if (text == "random")
    return CacheEviction::Random;
  throw std::invalid_argument("unknown eviction policy '" + text +
                              "' (choose none, lru, lrw or random)");
}

CacheValueFormat parseCacheValueFormat(const std::string& text) {
  if (text == "fp32")
    return CacheValueFormat::Fp32;
  if (text == "fp16")
    return CacheValueFormat::Fp16;
  throw std::invalid_argument("unknown --value-format '" + text + "' (choose fp32 or fp16)");
}

CacheClock parseCacheClock(const std::string& text) {
  if (text == "frame")
    return CacheClock::Frame;
  if (text == "counter")
    return CacheClock::Counter;
  throw std::invalid_argument("unknown --clock '" + text + "' (choose frame or counter)");
}

const char* tileFilterName(TileFilter filter) {
  return filter == TileFilter::Bilinear ? "bilinear" : "nearest";
}

const char* tileStorageName(TileStorage storage) {
  switch (storage) {
    case TileStorage::Entry:
      return "entry";
    case TileStorage::Buffer:
      return "buffer";
    case TileStorage::Texture2D:
      return "texture2d";
    case TileStorage::Texture3D:
      return "texture3d";
  }
  return "entry";
}

TileFilter parseTileFilter(const std::string& text) {
  if (text == "nearest")
    return TileFilter::Nearest;
  if (text == "bilinear")
    return TileFilter::Bilinear;
  throw std::invalid_argument("unknown --filter '" + text + "' (choose nearest or bilinear)");
}

TileStorage parseTileStorage(const std::string& text) {
  for (TileStorage storage :
       {TileStorage::Entry, TileStorage::Buffer, TileStorage::Texture2D, TileStorage::Texture3D})
    if (text == tileStorageName(storage))
      return storage;
  throw std::invalid_argument("unknown --tile-storage '" + text +
                              "' (choose entry, buffer, texture2d or texture3d)");
}

const char* tileFillName(TileFill fill) {
  return fill == TileFill::Deferred ? "deferred" : "subgroup";
}

TileFill parseTileFill(const std::string& text) {
  if (text == "subgroup")
    return TileFill::Subgroup;
  if (text == "deferred")
    return TileFill::Deferred;
  throw std::invalid_argument("unknown --tile-fill '" + text + "' (choose subgroup or deferred)");
}

CacheRefresh cacheRefreshOf(const CacheOptions& cache) {
  if (cache.mode != CacheMode::Texel || cache.filter != CacheFilter::Nearest)
    return {};
  if (cache.refreshFrames)
    return {*cache.refreshFrames, *cache.refreshFrames};
  return {0, kDefaultVoxelRefreshFrames};
}

std::string cacheRefreshText(const CacheRefresh& refresh) {
  auto period = [](std::uint32_t frames) {
    return frames == 0 ? std::string("never") : "every " + std::to_string(frames) + " frames";
  };
  if (refresh.uv == refresh.voxel)
    return "keys refreshed " + period(refresh.uv);
  return "keys refreshed: uv " + period(refresh.uv) + ", voxel " + period(refresh.voxel);
}

void validateCacheOptions(const CacheOptions& cache) {
  if (cache.probe < 1 || cache.probe > gpu::kCacheMaxProbe)
    throw std::invalid_argument("--probe must be 1.." + std::to_string(gpu::kCacheMaxProbe) +
                                ", not " + std::to_string(cache.probe));
  if (cache.entries && *cache.entries <= cache.probe)
    throw std::invalid_argument("--cache-entries (" + std::to_string(*cache.entries) +
                                ") must exceed the probe distance (" + std::to_string(cache.probe) +
                                ")");
  if (!std::isfinite(cache.mipBias))
    throw std::invalid_argument("--mip-bias must be finite");
  if (cache.refreshFrames.value_or(0) > 0 && cache.mode == CacheMode::Tile)
    throw std::invalid_argument(
        "--cache-refresh is the texel cache's (--cache texel): a tile's "
        "texels are computed at their centres");
  if (cache.refreshFrames.value_or(0) > 0 && cache.filter != CacheFilter::Nearest)
    throw std::invalid_argument(std::string("--cache-refresh with --cache-filter ") +
                                cacheFilterName(cache.filter) +
                                ": the filters blend or pick entries by their cells' centres, "
                                "so their entries are evaluated there; use --cache-filter nearest");
  if (cache.mode == CacheMode::Tile && cache.filter != CacheFilter::Nearest)
    throw std::invalid_argument(std::string("--cache-filter ") + cacheFilterName(cache.filter) +
                                " is the texel cache's (--cache texel); the tile cache filters "
                                "with --filter bilinear");
  if (cache.mode == CacheMode::Tile) {
    const std::string size =
        std::to_string(cache.tileWidth) + "x" + std::to_string(cache.tileHeight);
    if (cache.tileWidth == 0 || cache.tileHeight == 0 || cache.tileWidth > 64 ||
        cache.tileHeight > 64)
      throw std::invalid_argument("--tile takes sides of 1..64 texels, not " + size);
    if (cache.tileFilter == TileFilter::Bilinear && (cache.tileWidth < 2 || cache.tileHeight < 2))
      throw std::invalid_argument("--tile " + size +
                                  " with --filter bilinear: tiles overlap by one texel, so both "
                                  "sides need at least 2 texels");
    if (cache.groupByMaterial && cache.tileFill == TileFill::Deferred)
      throw std::invalid_argument(
          "--group-by-material orders the tiles a subgroup computes (--tile-fill subgroup); "
          "the deferred fill computes each queued tile on its own");
    if (cache.tileQueue < 1 || cache.tileQueue > (1u << 24))
      throw std::invalid_argument("--tile-queue must be 1..16777216 tiles, not " +
                                  std::to_string(cache.tileQueue));
    if (cache.testRepacks && (cache.testRepackPercent < 1 || cache.testRepackPercent > 100))
      throw std::invalid_argument("MEMOGRAPH_TEST_TILE_GIVE_UP must be 0..100 %, not " +
                                  std::to_string(cache.testRepackPercent));
    if (cache.testRepacks && cache.tileFill == TileFill::Deferred)
      throw std::invalid_argument(
          "MEMOGRAPH_TEST_TILE_GIVE_UP gives up the subgroup fill's tiles (--tile-fill subgroup)");
  }
  if (cache.clockShift && *cache.clockShift > 32)
    throw std::invalid_argument("the cache's clock shift must be 0..32, not " +
                                std::to_string(*cache.clockShift));
}

std::uint32_t defaultCacheEntries(CacheMode mode) {
  return mode == CacheMode::Texel ? kDefaultTexelCacheEntries : kDefaultCacheEntries;
}

CacheClock cacheClockOf(const CacheOptions& options, bool bufferInt64Atomics) {
  if (options.clock)
    return *options.clock;
  if (options.mode == CacheMode::Texel && options.eviction == CacheEviction::Lru)
    return CacheClock::Frame;
  return bufferInt64Atomics ? CacheClock::Counter : CacheClock::Frame;
}

std::uint32_t cacheClockShift(const CacheOptions& options, std::uint64_t lookupsPerFrame) {
  if (options.clockShift)
    return *options.clockShift;
  if (options.eviction == CacheEviction::Lrw)
    return 0u;
  if (lookupsPerFrame == 0)
    return 16u;
  const long bits = std::lround(std::log2(double(lookupsPerFrame)));
  return std::uint32_t(std::clamp(bits - 10, 0l, 32l));
}

CacheOptions resolveCacheOptions(CacheOptions options, bool bufferInt64Atomics,
                                 std::uint64_t lookupsPerFrame) {
  options.clock = cacheClockOf(options, bufferInt64Atomics);
  options.clockShift = cacheClockShift(options, lookupsPerFrame);
  return options;
}

std::uint32_t cacheValueWords(const CacheOptions& options, std::uint32_t valueCount) {
  return options.valueFormat == CacheValueFormat::Fp16 ? (valueCount + 1) / 2 : valueCount;
}

std::uint32_t cacheTexelsPerEntry(const CacheOptions& options) {
  return options.mode == CacheMode::Tile ? options.tileWidth * options.tileHeight : 1;
}

// The value words after the header: MG_CACHE_ENTRY_WORDS.
static std::uint32_t entryValueWords(const CacheOptions& options, std::uint32_t valueCount) {
  if (options.mode == CacheMode::Tile && options.tileStorage != TileStorage::Entry)
    return 0;
  return cacheTexelsPerEntry(options) * cacheValueWords(options, valueCount);
}

std::uint32_t cacheEntryWords(const CacheOptions& options, std::uint32_t valueCount) {
  // The subgroup tile fill's count of stored texels follows the header (texel_cache.glsl
  // kCacheTileCount); the deferred fill counts in its queue instead.
  const bool tileCount = options.mode == CacheMode::Tile && options.tileFill != TileFill::Deferred;
  return (options.updateCounter ? gpu::kCacheEntryHeaderWithCounter : gpu::kCacheEntryHeader) +
         (tileCount ? gpu::kCacheEntryTileCountWords : 0) + entryValueWords(options, valueCount);
}

std::vector<std::string> cacheShaderDefines(const CacheOptions& cache, std::uint32_t valueCount) {
  if (cache.mode == CacheMode::None)
    return {};
  std::vector<std::string> defines = {
      cache.mode == CacheMode::Tile ? "MG_CACHE_TILE=1" : "MG_CACHE_TEXEL=1",
      "MG_CACHE_VALUES=" + std::to_string(valueCount),
      "MG_CACHE_PROBE=" + std::to_string(cache.probe),
      "MG_CACHE_EVICTION=" + std::to_string(static_cast<std::uint32_t>(cache.eviction))};
  if (cache.updateCounter)
    defines.push_back("MG_CACHE_UPDATE_COUNTER=1");
  if (cache.valueFormat == CacheValueFormat::Fp16)
    defines.push_back("MG_CACHE_VALUE_FP16=1");
  if (cacheClockOf(cache) == CacheClock::Counter) {
    defines.push_back("MG_CACHE_CLOCK_COUNTER=1");
    defines.push_back("MG_CACHE_CLOCK_SHIFT=" + std::to_string(cacheClockShift(cache)));
  }
  if (cache.snapUv)
    defines.push_back("MG_CACHE_SNAP_UV=1");
  if (cache.secondaryOnly)
    defines.push_back("MG_CACHE_SECONDARY_ONLY=1");
  const CacheRefresh refresh = cacheRefreshOf(cache);
  if (refresh.uv > 0)
    defines.push_back("MG_CACHE_REFRESH_UV=" + std::to_string(refresh.uv));
  if (refresh.voxel > 0)
    defines.push_back("MG_CACHE_REFRESH_VOXEL=" + std::to_string(refresh.voxel));
  if (cache.mode == CacheMode::Texel && cache.filter != CacheFilter::Nearest)
    defines.push_back("MG_CACHE_FILTER=" +
                      std::to_string(static_cast<std::uint32_t>(cache.filter)));
  if (cache.mode == CacheMode::Tile) {
    defines.push_back("MG_CACHE_ENTRY_WORDS=" + std::to_string(entryValueWords(cache, valueCount)));
    defines.push_back("MG_TILE_W=" + std::to_string(cache.tileWidth));
    defines.push_back("MG_TILE_H=" + std::to_string(cache.tileHeight));
    defines.push_back("MG_TILE_STORAGE=" +
                      std::to_string(static_cast<std::uint32_t>(cache.tileStorage)));
    if (cache.tileStorage == TileStorage::Texture2D || cache.tileStorage == TileStorage::Texture3D)
      defines.push_back("MG_CACHE_VALUES_IN_IMAGE=1");  // cacheFence orders image memory too
    if (cache.tileFilter == TileFilter::Bilinear)
      defines.push_back("MG_TILE_BILINEAR=1");
    if (cache.groupByMaterial)
      defines.push_back("MG_TILE_GROUP_BY_MATERIAL=1");
    if (cache.tileFill == TileFill::Deferred) {
      defines.push_back("MG_TILE_FILL_DEFERRED=1");
      defines.push_back("MG_TILE_QUEUE_CAPACITY=" + std::to_string(cache.tileQueue));
    }
    if (cache.testRepacks)
      defines.push_back("MG_TILE_TEST_REPACKS=1");
    if (cache.testRepacks && cache.testRepackPercent < 100)
      defines.push_back("MG_TILE_TEST_REPACK_PERCENT=" + std::to_string(cache.testRepackPercent));
    if (cache.testPartialSubgroups)
      defines.push_back("MG_TILE_TEST_PARTIAL_SUBGROUPS=1");
    if (cache.tileStorage == TileStorage::Texture2D || cache.tileStorage == TileStorage::Texture3D)
      defines.push_back(cache.valueFormat == CacheValueFormat::Fp16
                            ? "MG_TILE_IMAGE_FORMAT=rgba16f"
                            : "MG_TILE_IMAGE_FORMAT=rgba32f");
  }
  return defines;
}

}  // namespace memograph::runtime
