// The GPU side of material graph memoization (thesis §5.3-5.4) as one render sets it up:
// checks the cache options against the device, picks the path tracer's cache defines, and
// owns the entry buffer, the tile cache's texel buffer or storage image (§5.4.1), the
// per-frame log of computed tiles that counts duplicates (§6.7.2) and the deferred fill's
// queue of missing tiles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/memo/cache_options.h"
#include "runtime/renderer.h"
#include "runtime/trace/render_stats.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/storage_image.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// Throws std::invalid_argument naming the option when `options` cannot run on the device
// (validateCacheOptions checks what needs no device).
void validateCacheOnDevice(const VulkanContext& context, const CacheOptions& options);

class MaterialCache {
 public:
  // `valueCount`: floats per texel, the largest cacheable material's written outputs.
  // Throws std::invalid_argument naming the option when the device cannot run it.
  MaterialCache(const VulkanContext& context, const CacheOptions& options,
                std::uint32_t valueCount);

  // MG_CACHE_* / MG_TILE_* for path_tracer.glsl; empty without a cache.
  const std::vector<std::string>& defines() const { return defines_; }
  // Entries S for FrameConstants::cache.x (0: no cache) and the storage image's tiles per
  // row for cache.w.
  std::uint32_t entryCount() const { return entryCount_; }
  std::uint32_t tilesPerRow() const { return tilesPerRow_; }

  // Bindings kBindingCache, kBindingTileTexels and kBindingTileLog (small dummies when
  // unused) and kBindingTileImage (VK_NULL_HANDLE unless tiles live in an image).
  const GpuBuffer& entries() const { return entries_; }
  const GpuBuffer& tileTexels() const { return tileTexels_; }
  const GpuBuffer& tileLog() const { return tileLog_; }
  // Binding kBindingTileQueue: the deferred fill's queue (a small dummy otherwise), and the
  // fill pass's launch: rows of gpu::kFillRowInvocations invocations, one per texel of
  // every queue slot (0 without the deferred fill: no fill pass).
  const GpuBuffer& tileQueue() const { return tileQueue_; }
  std::uint32_t tileFillRows() const { return tileFillRows_; }
  VkImageView tileImageView() const { return tileImage_.view.get(); }

  // The clears before a frame's trace: every entry empty (key 0, clock 0) before the first
  // frame; the tile log and the fill queue's count before every frame. The caller orders them
  // before the trace.
  void recordClears(VkCommandBuffer commands, bool firstFrame) const;

  // The cache's settings and memory in the render's statistics.
  void describe(RenderStats& stats) const;

 private:
  CacheOptions options_;
  std::uint32_t valueCount_ = 1;
  std::uint32_t entryCount_ = 0;
  std::uint32_t tilesPerRow_ = 0;
  std::uint64_t bytes_ = 0;
  std::vector<std::string> defines_;
  GpuBuffer entries_;
  GpuBuffer tileTexels_;
  GpuBuffer tileLog_;
  GpuBuffer tileQueue_;
  std::uint32_t tileFillRows_ = 0;
  StorageImage tileImage_;  // --tile-storage texture2d|texture3d only
};

}  // namespace memograph::runtime
