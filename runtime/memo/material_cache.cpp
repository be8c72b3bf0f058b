#include "runtime/memo/material_cache.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "runtime/shaders/shared_types.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

constexpr VkBufferUsageFlags kStorage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

// A cache buffer of `bytes`, checked before allocating (checkBufferSize) under the name of
// the option that sized it: the descriptor set checks every binding again, later and
// without the option's name.
GpuBuffer deviceBuffer(const VulkanContext& context, std::uint64_t bytes,
                       const std::string& sizedBy) {
  checkBufferSize(context, bytes, sizedBy, true);
  return GpuBuffer(context, std::max<VkDeviceSize>(bytes, 16), kStorage,
                   VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
}

// S: the given --cache-entries, or defaultCacheEntries(mode) halved while `bytesPerEntry`
// times the count exceeds the device's storage-buffer range or a quarter of its largest
// device-local heap (never below twice the probe distance; deviceBuffer refuses what still
// does not fit).
std::uint32_t entryCountFor(const VulkanContext& context, const CacheOptions& options,
                            std::uint64_t bytesPerEntry) {
  if (options.entries)
    return *options.entries;
  std::uint64_t limit = context.info().limits.maxStorageBufferRange;
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(context.physicalDevice(), &memory);
  std::uint64_t deviceLocal = 0;
  for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h)
    if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      deviceLocal = std::max<std::uint64_t>(deviceLocal, memory.memoryHeaps[h].size);
  if (deviceLocal > 0)
    limit = limit > 0 ? std::min(limit, deviceLocal / 4) : deviceLocal / 4;
  std::uint32_t count = defaultCacheEntries(options.mode);
  while (limit > 0 && std::uint64_t(count) * bytesPerEntry > limit && count / 2 > 2 * options.probe)
    count /= 2;
  return count;
}

// The deferred fill's launch: one invocation per texel of every queue slot, in rows of
// kFillRowInvocations (0 rows: no fill pass).
std::uint32_t fillRows(const CacheOptions& options) {
  if (options.mode != CacheMode::Tile || options.tileFill != TileFill::Deferred)
    return 0;
  const std::uint64_t invocations = std::uint64_t(options.tileQueue) * cacheTexelsPerEntry(options);
  return std::uint32_t(std::min<std::uint64_t>(
      (invocations + gpu::kFillRowInvocations - 1) / gpu::kFillRowInvocations, 0xFFFFFFFFu));
}

// The stage the path tracer runs in on this context's backend.
VkShaderStageFlagBits traceStage(const VulkanContext& context) {
  return context.backend() == Backend::RayQuery ? VK_SHADER_STAGE_COMPUTE_BIT
                                                : VK_SHADER_STAGE_RAYGEN_BIT_KHR;
}

void checkTileOptions(const VulkanContext& context, const CacheOptions& options) {
  const DeviceInfo& info = context.info();
  const std::uint32_t texels = options.tileWidth * options.tileHeight;
  const std::string size =
      std::to_string(options.tileWidth) + "x" + std::to_string(options.tileHeight);
  // §5.4.3: one lane per texel of a tile (the deferred fill has one invocation per texel
  // and no such limit).
  if (options.tileFill != TileFill::Deferred && texels > info.subgroupSize)
    throw std::invalid_argument("--tile " + size + " has " + std::to_string(texels) +
                                " texels, more than the " + std::to_string(info.subgroupSize) +
                                " lanes of a subgroup on " + info.name +
                                " (the subgroup computes a tile with one lane per texel)");
  constexpr VkSubgroupFeatureFlags kNeeded =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT |
      VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_SHUFFLE_BIT |
      VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  const VkShaderStageFlagBits stage = traceStage(context);
  if (options.tileFill != TileFill::Deferred &&
      ((info.subgroupOperations & kNeeded) != kNeeded || !(info.subgroupStages & stage)))
    throw std::invalid_argument(
        "--cache tile needs subgroup ballot, shuffle, vote and arithmetic in the " +
        std::string(stage == VK_SHADER_STAGE_COMPUTE_BIT ? "compute" : "ray-generation") +
        " stage, which " + info.name + " does not offer" +
        (stage == VK_SHADER_STAGE_RAYGEN_BIT_KHR ? " (try --backend query or --tile-fill deferred)"
                                                 : ""));
}

// The device must launch the deferred fill's rows in one go.
void checkTileFillLaunch(const VulkanContext& context, const CacheOptions& options) {
  const DeviceInfo& info = context.info();
  const std::uint64_t rows = fillRows(options);
  const bool compute = traceStage(context) == VK_SHADER_STAGE_COMPUTE_BIT;
  const std::uint64_t maxRows = compute ? info.limits.maxComputeWorkGroupCount[1]
                                        : std::uint64_t(info.limits.maxComputeWorkGroupCount[1]) *
                                              info.limits.maxComputeWorkGroupSize[1];
  const std::uint64_t maxInvocations =
      std::min(maxRows * gpu::kFillRowInvocations,
               compute ? ~std::uint64_t(0)
                       : std::uint64_t(info.rayTracingProperties.maxRayDispatchInvocationCount));
  // maxInvocations is at most maxRows rows: one comparison covers both limits.
  const std::uint64_t invocations = rows * gpu::kFillRowInvocations;
  if (invocations > maxInvocations)
    throw std::invalid_argument("--tile-queue " + std::to_string(options.tileQueue) +
                                " with --tile " + std::to_string(options.tileWidth) + "x" +
                                std::to_string(options.tileHeight) + " needs a fill pass of " +
                                std::to_string(invocations) + " invocations, more than " +
                                info.name + " launches at once (" + std::to_string(maxInvocations) +
                                "): use a shorter queue or smaller tiles");
}

VkFormat imageFormat(const CacheOptions& options) {
  return options.valueFormat == CacheValueFormat::Fp16 ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                       : VK_FORMAT_R32G32B32A32_SFLOAT;
}

}  // namespace

void validateCacheOnDevice(const VulkanContext& context, const CacheOptions& options) {
  if (options.mode == CacheMode::Tile)
    checkTileOptions(context, options);
  if (options.mode == CacheMode::Tile && options.tileFill == TileFill::Deferred)
    checkTileFillLaunch(context, options);
}

MaterialCache::MaterialCache(const VulkanContext& context, const CacheOptions& options,
                             std::uint32_t valueCount)
    : options_(options), valueCount_(std::max(1u, valueCount)) {
  validateCacheOptions(options);
  validateCacheOnDevice(context, options);
  const bool tile = options.mode == CacheMode::Tile;
  const bool enabled = options.mode != CacheMode::None;
  const std::uint32_t texels = cacheTexelsPerEntry(options);
  const TileStorage storage = tile ? options.tileStorage : TileStorage::Entry;
  const std::uint64_t stride = cacheEntryWords(options, valueCount_);
  const std::uint64_t texelBytesPerEntry =
      std::uint64_t(texels) * cacheValueWords(options, valueCount_) * sizeof(std::uint32_t);
  entryCount_ =
      enabled ? entryCountFor(context, options,
                              std::max(stride * sizeof(std::uint32_t),
                                       storage == TileStorage::Buffer ? texelBytesPerEntry : 0))
              : 0;
  defines_ = cacheShaderDefines(options, valueCount_);

  // Without a cache the bindings still need buffers: small ones nobody reads.
  const std::uint64_t entryBytes = std::uint64_t(entryCount_) * stride * sizeof(std::uint32_t);
  entries_ = deviceBuffer(context, enabled ? entryBytes : stride * sizeof(std::uint32_t),
                          "--cache-entries " + std::to_string(entryCount_));
  bytes_ = entryBytes;  // 0 without a cache (no entries)
  const std::uint64_t texelBytes = std::uint64_t(entryCount_) * texelBytesPerEntry;
  tileTexels_ = deviceBuffer(
      context, storage == TileStorage::Buffer ? texelBytes : 16,
      "--cache-entries " + std::to_string(entryCount_) + " with --tile-storage buffer");
  if (storage == TileStorage::Buffer)
    bytes_ += texelBytes;
  tileLog_ = deviceBuffer(context, tile ? gpu::kTileLogEntries * sizeof(std::uint32_t) : 16,
                          "the tile log");
  const bool deferred = tile && options.tileFill == TileFill::Deferred;
  const std::uint64_t queueBytes =
      sizeof(gpu::TileQueueHeader) + std::uint64_t(options.tileQueue) * sizeof(gpu::TileFillItem);
  tileQueue_ = deviceBuffer(context, deferred ? queueBytes : sizeof(gpu::TileQueueHeader),
                            "--tile-queue " + std::to_string(options.tileQueue));
  if (deferred)
    bytes_ += queueBytes;
  tileFillRows_ = fillRows(options);

  if (storage == TileStorage::Texture2D || storage == TileStorage::Texture3D) {
    // Four values per image texel; a texel's groups side by side in x (2D) or stacked in z
    // (3D). Tiles row by row, as square an image as the tile shape allows.
    const bool is3D = storage == TileStorage::Texture3D;
    const std::uint32_t groups = (valueCount_ + 3) / 4;
    const std::uint64_t tileWidth = std::uint64_t(options.tileWidth) * (is3D ? 1 : groups);
    const std::uint64_t tileHeight = options.tileHeight;
    std::uint64_t perRow = std::max<std::uint64_t>(
        1, std::uint64_t(std::ceil(std::sqrt(double(entryCount_) * tileHeight / tileWidth))));
    perRow = std::min<std::uint64_t>(perRow, entryCount_);
    const std::uint64_t rows = (entryCount_ + perRow - 1) / perRow;
    const std::uint64_t width = perRow * tileWidth, height = rows * tileHeight;
    const VkPhysicalDeviceLimits& limits = context.info().limits;
    const std::uint64_t maxSide = is3D ? limits.maxImageDimension3D : limits.maxImageDimension2D;
    if (width > maxSide || height > maxSide || (is3D && groups > maxSide))
      throw std::invalid_argument("--tile-storage " + std::string(tileStorageName(storage)) + ": " +
                                  std::to_string(entryCount_) + " tiles need a " +
                                  std::to_string(width) + "x" + std::to_string(height) +
                                  (is3D ? "x" + std::to_string(groups) : std::string()) +
                                  " image, over the device's limit of " + std::to_string(maxSide) +
                                  " (use fewer --cache-entries or a buffer storage)");
    tilesPerRow_ = static_cast<std::uint32_t>(perRow);
    VkFormatProperties formatProperties;
    vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), imageFormat(options),
                                        &formatProperties);
    if (!(formatProperties.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
      throw std::invalid_argument(context.info().name + " cannot use " +
                                  cacheValueFormatName(options.valueFormat) +
                                  " RGBA storage images (--tile-storage)");

    tileImage_ = createStorageImage(
        context, is3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D, imageFormat(options),
        {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), is3D ? groups : 1u},
        "tile cache image");
    bytes_ += tileImage_.bytes;
  }
}

void MaterialCache::recordClears(VkCommandBuffer commands, bool firstFrame) const {
  if (firstFrame)
    vkCmdFillBuffer(commands, entries_.buffer(), 0, VK_WHOLE_SIZE, gpu::kCacheKeyEmpty);
  if (options_.mode == CacheMode::Tile) {
    vkCmdFillBuffer(commands, tileLog_.buffer(), 0, VK_WHOLE_SIZE, 0);
    // The deferred fill's queue: only its count (each queued item is written whole).
    if (tileFillRows_ > 0)
      vkCmdFillBuffer(commands, tileQueue_.buffer(), 0, sizeof(gpu::TileQueueHeader), 0);
  }
}

void MaterialCache::describe(RenderStats& stats) const {
  if (options_.mode == CacheMode::None)
    return;
  stats.cache = cacheModeName(options_.mode);
  stats.cacheEviction = cacheEvictionName(options_.eviction);
  stats.cacheEntries = entryCount_;
  stats.cacheEntriesFitted = !options_.entries && entryCount_ != defaultCacheEntries(options_.mode);
  stats.cacheProbe = options_.probe;
  stats.cacheReadCheck = options_.updateCounter ? "counter" : "key";
  stats.cacheValueCount = valueCount_;
  stats.cacheBytes = bytes_;
  stats.cacheValueFormat = cacheValueFormatName(options_.valueFormat);
  stats.cacheClock = cacheClockName(cacheClockOf(options_));
  stats.cacheSnapUv = options_.snapUv;
  stats.cacheSecondaryOnly = options_.secondaryOnly;
  stats.cacheFilter = cacheFilterName(options_.filter);
  stats.cacheKeyDomains = cacheKeyDomainsName(options_.keyDomains);
  if (options_.mode == CacheMode::Texel)
    stats.cacheRefresh = cacheRefreshText(cacheRefreshOf(options_));
  if (options_.mode == CacheMode::Tile)
    stats.cacheTile =
        std::to_string(options_.tileWidth) + "x" + std::to_string(options_.tileHeight) + " " +
        tileFilterName(options_.tileFilter) + " " + tileStorageName(options_.tileStorage) +
        (options_.groupByMaterial ? " grouped" : "") +
        (options_.tileFill == TileFill::Deferred
             ? " deferred (queue " + std::to_string(options_.tileQueue) + ")"
             : "");
}

}  // namespace memograph::runtime
