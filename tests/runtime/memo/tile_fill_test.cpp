// The tile cache's deferred fill (--tile-fill deferred, docs/design/path-tracer.md) on lavapipe: a
// missed tile is queued once per frame and computed by a second pass after the frame's
// trace, so it needs no subgroup and runs in the raygen of the ray-tracing pipeline with
// callable materials too (the configuration NVIDIA offers), with tiles larger than
// lavapipe's 8-lane subgroups. Its picture equals the texel cache's within the tile cache's
// own tolerance, a tile becomes readable only in the frame after its request, and a full
// queue leaves the extra misses to evaluate their own hits.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "texel_cache_scenes.h"

namespace memograph::runtime {
namespace {

using testing::cacheOptions;
using testing::cacheSettings;
using testing::expectConsistentCounters;
using testing::meanFlip;
using testing::stripesGraph;
using testing::wallScene;

RendererOptions deferredOptions(Backend backend, std::uint32_t width, std::uint32_t height,
                                TileFilter filter = TileFilter::Nearest) {
  RendererOptions options = cacheOptions(CacheMode::Tile, backend);
  options.cache.tileWidth = width;
  options.cache.tileHeight = height;
  options.cache.tileFilter = filter;
  options.cache.tileFill = TileFill::Deferred;
  return options;
}

// Frame 0 finds nothing (tiles are published after the frame's trace), each queued tile is
// a distinct missed tile (never more tiles than misses, no duplicates: the frame's tile log
// lets only the first request queue), and the camera being still, the last frame hits.
void expectDeferredCounters(const RenderStats& stats) {
  expectConsistentCounters(stats);
  ASSERT_FALSE(stats.frames.empty());
  EXPECT_EQ(stats.frames.front().cacheHits, 0u);
  EXPECT_GT(stats.frames.front().cacheTilesComputed, 0u);
  std::uint64_t queued = 0;
  for (const FrameStats& f : stats.frames) {
    // The fill pass publishes every queued tile once (its last texel's count), in the frame.
    queued += f.cacheTilesComputed;
    EXPECT_EQ(f.cacheTilesPublished, queued) << "frame " << f.frame;
    EXPECT_LE(f.cacheTilesComputed, f.cacheMisses) << "frame " << f.frame;
    EXPECT_EQ(f.cacheDuplicateTiles, 0u) << "frame " << f.frame;
    EXPECT_EQ(f.cacheTileRepacks, 0u) << "frame " << f.frame;
  }
  EXPECT_GT(stats.frames.back().cacheHitRate(), 0.99);
}

// The same bounds as TileCache.NearestPictureEqualsTheTexelCacheWithinTolerance: mean
// LDR-FLIP below 0.07 against the texel cache and 0.06 against no cache, nearest and
// bilinear. The deferred fill computes the same texels (eq. 5.16-5.17) as the subgroup.
TEST(TileFill, DeferredPictureEqualsTheTexelCacheWithinTolerance) {
  Scene scene = wallScene(stripesGraph(), true);
  RenderResult none = Renderer(cacheOptions(CacheMode::None, Backend::RayQuery))
                          .render(scene, cacheSettings(6, 3, 2));
  RenderResult texel = Renderer(cacheOptions(CacheMode::Texel, Backend::RayQuery))
                           .render(scene, cacheSettings(6, 3, 2));
  for (auto [w, h, filter] :
       {std::tuple{4u, 2u, TileFilter::Nearest}, std::tuple{3u, 3u, TileFilter::Bilinear}}) {
    RenderResult tile = Renderer(deferredOptions(Backend::RayQuery, w, h, filter))
                            .render(scene, cacheSettings(6, 3, 2));
    expectDeferredCounters(tile.stats);
    double flipTexel = meanFlip(texel.image, tile.image);
    double flipNone = meanFlip(none.image, tile.image);
    std::printf(
        "%s: mean LDR-FLIP %.4f vs texel cache, %.4f vs none; frame 0: %llu misses, "
        "%llu tiles queued; last frame hit rate %.2f %%\n",
        tile.stats.cacheTile.c_str(), flipTexel, flipNone,
        (unsigned long long)tile.stats.frames.front().cacheMisses,
        (unsigned long long)tile.stats.frames.front().cacheTilesComputed,
        100.0 * tile.stats.frames.back().cacheHitRate());
    EXPECT_NE(tile.stats.cacheTile.find("deferred"), std::string::npos);
    EXPECT_LT(flipTexel, 0.07);
    EXPECT_LT(flipNone, 0.06);
  }
}

// The ray-tracing pipeline with callable materials, lavapipe's raygen having no subgroup
// operations at all: 4x4 tiles (16 texels, twice lavapipe's subgroup) are filled by the
// second raygen, which calls the same callables. The picture equals the query backend's
// deferred picture within 0.01 (the same texels; path sampling differs between backends
// only by traversal order) and the uncached one within 0.06.
TEST(TileFill, DeferredRunsInTheRaygenWithCallablesAndTilesLargerThanTheSubgroup) {
  Scene scene = wallScene(stripesGraph(), true);
  RenderResult none =
      Renderer(cacheOptions(CacheMode::None, Backend::RayQuery)).render(scene, cacheSettings(4, 2));
  RenderResult query =
      Renderer(deferredOptions(Backend::RayQuery, 4, 4)).render(scene, cacheSettings(4, 2));
  RendererOptions options = deferredOptions(Backend::RayTracingPipeline, 4, 4);
  options.materialDispatch = MaterialDispatch::Callable;
  RenderResult raygen = Renderer(options).render(scene, cacheSettings(4, 2));
  EXPECT_EQ(raygen.stats.materialDispatch, "callable");
  expectDeferredCounters(raygen.stats);
  double flipQuery = meanFlip(query.image, raygen.image);
  double flipNone = meanFlip(none.image, raygen.image);
  std::printf(
      "%s on the raygen with callables: mean LDR-FLIP %.4f vs the query backend, %.4f vs "
      "none\n",
      raygen.stats.cacheTile.c_str(), flipQuery, flipNone);
  EXPECT_LT(flipQuery, 0.01);
  EXPECT_LT(flipNone, 0.06);
}

// A queue of 2 tiles: per frame at most 2 tiles are computed, every other first request
// gives its locked entry back (a fallback) and its lane evaluates the hit itself, so the
// picture stays the uncached one's within the cache's bound and the occupancy counts only
// published tiles.
TEST(TileFill, AFullQueueLeavesTheRestToEvaluateTheirHits) {
  Scene scene = wallScene(stripesGraph(), true);
  RenderResult none =
      Renderer(cacheOptions(CacheMode::None, Backend::RayQuery)).render(scene, cacheSettings(3, 2));
  RendererOptions options = deferredOptions(Backend::RayQuery, 2, 2);
  options.cache.tileQueue = 2;
  RenderResult small = Renderer(options).render(scene, cacheSettings(3, 2));
  expectConsistentCounters(small.stats);
  std::uint64_t published = 0;
  for (const FrameStats& f : small.stats.frames) {
    EXPECT_LE(f.cacheTilesComputed, 2u) << "frame " << f.frame;
    EXPECT_GT(f.cacheTileFallbacks, 0u) << "frame " << f.frame;
    published += f.cacheTilesComputed;
    EXPECT_EQ(f.cacheTilesPublished, published) << "frame " << f.frame;
    EXPECT_LE(f.cacheOccupancy, published) << "frame " << f.frame;
  }
  double flip = meanFlip(none.image, small.image);
  std::printf("%s: mean LDR-FLIP %.4f vs none, %llu tiles published in %zu frames\n",
              small.stats.cacheTile.c_str(), flip, (unsigned long long)published,
              small.stats.frames.size());
  EXPECT_LT(flip, 0.06);
}

// An insert's lock beside a locked entry, and one lost to another invocation's lock, are
// counted (gpu::Counters::cacheLocksBesideALock, cacheLocksContended). The deferred fill
// keeps every queued tile's entry locked until the fill after the frame, so in a cache of
// one probe range (9 entries, D = 8) a frame's later requests find locked entries beside
// the one they choose, under every policy; random picks a locked entry too, and loses it.
TEST(TileFill, LocksBesideAndLostToQueuedTilesAreCounted) {
  Scene scene = wallScene(stripesGraph(), true);
  for (CacheEviction eviction : {CacheEviction::Lru, CacheEviction::Random}) {
    RendererOptions options = deferredOptions(Backend::RayQuery, 2, 2);
    options.cache.entries = 9;
    options.cache.eviction = eviction;
    RenderResult r = Renderer(options).render(scene, cacheSettings(2, 2));
    expectConsistentCounters(r.stats);
    const FrameStats& f = r.stats.frames.front();
    std::printf("9 entries, %s: %llu locks beside a lock, %llu lost, %llu tiles queued\n",
                cacheEvictionName(eviction), (unsigned long long)f.cacheLocksBesideALock,
                (unsigned long long)f.cacheLocksContended,
                (unsigned long long)f.cacheTilesComputed);
    EXPECT_GT(f.cacheLocksBesideALock, 0u) << cacheEvictionName(eviction);
    EXPECT_LE(f.cacheTilesComputed, 9u);  // a locked entry is never chosen twice
    if (eviction == CacheEviction::Random) {
      EXPECT_GT(f.cacheLocksContended, 0u);
    }
  }
}

// What the deferred fill does not combine with is refused with the reason; so is a fill
// pass larger than the device launches (65536 slots of 64x64 texels: 2^28 invocations in
// 65536 rows of 4096, one row more than a compute dispatch may have).
TEST(TileFill, RefusesGroupingByMaterialAnEmptyQueueAndAnOversizedFill) {
  Renderer huge(deferredOptions(Backend::RayQuery, 64, 64));
  try {
    huge.render(wallScene(stripesGraph(), false), cacheSettings(1, 1));
    ADD_FAILURE() << "a fill pass of 2^28 invocations was launched";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--tile-queue 65536 with --tile 64x64"), std::string::npos)
        << e.what();
  }
  CacheOptions cache;
  cache.mode = CacheMode::Tile;
  cache.tileFill = TileFill::Deferred;
  cache.groupByMaterial = true;
  try {
    validateCacheOptions(cache);
    ADD_FAILURE() << "--group-by-material with the deferred fill was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--group-by-material"), std::string::npos) << e.what();
  }
  cache.groupByMaterial = false;
  cache.tileQueue = 0;
  EXPECT_THROW(validateCacheOptions(cache), std::invalid_argument);
  EXPECT_EQ(parseTileFill("deferred"), TileFill::Deferred);
  EXPECT_THROW(parseTileFill("later"), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime
