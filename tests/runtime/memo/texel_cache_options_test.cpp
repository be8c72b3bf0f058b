// The texel cache's options on lavapipe: fp16 values (§5.3.1), the 64-bit counter
// clock (§5.3.3), texel-centre snapping and secondary-only caching (§6.1), the occupancy
// counter, the miss view of Fig. 6.9, and the floor run (no graph evaluated).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/shaders/shared_types.h"
#include "texel_cache_scenes.h"

namespace memograph::runtime {
namespace {

using testing::meanFlip;
using testing::stripesGraph;
using testing::wallScene;

RendererOptions texelCache(std::uint32_t entries = 1u << 16,
                           CacheEviction eviction = CacheEviction::Lru) {
  RendererOptions options = testing::testOptions();
  options.cache.mode = CacheMode::Texel;
  options.cache.entries = entries;
  options.cache.eviction = eviction;
  return options;
}

RendererOptions noCache() {
  return testing::testOptions();
}

RenderSettings settings(std::uint32_t frames, std::uint32_t raysPerPath, std::uint32_t paths = 1,
                        std::uint32_t side = 24) {
  RenderSettings s;
  s.width = side;
  s.height = side;
  s.pathsPerPixel = paths;
  s.raysPerPath = raysPerPath;
  s.frames = frames;
  s.seed = 5;
  return s;
}

double meanHitRate(const RenderStats& stats, std::size_t from, std::size_t to) {
  double sum = 0;
  for (std::size_t f = from; f < to; ++f)
    sum += stats.frames[f].cacheHitRate();
  return sum / double(to - from);
}

std::size_t redPixels(const HdrImage& image) {
  std::size_t red = 0;
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4)
    red += image.rgba[i] == 1.0f && image.rgba[i + 1] == 0.0f && image.rgba[i + 2] == 0.0f;
  return red;
}

TEST(TexelCacheOptions, EntrySizesAndDefinesFollowTheOptions) {
  CacheOptions options;
  options.mode = CacheMode::Texel;
  EXPECT_TRUE(options.updateCounter);  // the default, from the H200 measurement
  EXPECT_EQ(cacheEntryWords(options, 12), gpu::kCacheEntryHeaderWithCounter + 12);
  options.updateCounter = false;
  EXPECT_EQ(cacheEntryWords(options, 12), gpu::kCacheEntryHeader + 12);
  options.valueFormat = CacheValueFormat::Fp16;
  EXPECT_EQ(cacheValueWords(options, 12), 6u);
  EXPECT_EQ(cacheValueWords(options, 5), 3u);  // the last word's high half unused
  options.updateCounter = true;
  EXPECT_EQ(cacheEntryWords(options, 5), gpu::kCacheEntryHeaderWithCounter + 3);
  {
    // Tiles: the subgroup fill's texel count follows the header (tile_cache.glsl
    // tileCountTexels); the deferred fill counts in its queue. 4x2 fp16 texels of 5 values.
    CacheOptions tile = options;
    tile.mode = CacheMode::Tile;
    tile.tileWidth = 4;
    tile.tileHeight = 2;
    EXPECT_EQ(cacheEntryWords(tile, 5),
              gpu::kCacheEntryHeaderWithCounter + gpu::kCacheEntryTileCountWords + 8 * 3);
    tile.tileStorage = TileStorage::Texture2D;
    EXPECT_EQ(cacheEntryWords(tile, 5),
              gpu::kCacheEntryHeaderWithCounter + gpu::kCacheEntryTileCountWords);
    tile.tileFill = TileFill::Deferred;
    EXPECT_EQ(cacheEntryWords(tile, 5), gpu::kCacheEntryHeaderWithCounter);
  }
  options.clock = CacheClock::Counter;
  options.clockShift = 3;
  options.snapUv = true;
  options.secondaryOnly = true;
  auto defines = cacheShaderDefines(options, 5);
  for (const char* expected :
       {"MG_CACHE_VALUE_FP16=1", "MG_CACHE_CLOCK_COUNTER=1", "MG_CACHE_CLOCK_SHIFT=3",
        "MG_CACHE_SNAP_UV=1", "MG_CACHE_SECONDARY_ONLY=1", "MG_CACHE_UPDATE_COUNTER=1"})
    EXPECT_NE(std::find(defines.begin(), defines.end(), expected), defines.end()) << expected;
  options.mode = CacheMode::None;
  EXPECT_TRUE(cacheShaderDefines(options, 5).empty());
  EXPECT_THROW(parseCacheValueFormat("fp8"), std::invalid_argument);
  EXPECT_THROW(parseCacheClock("x"), std::invalid_argument);
  EXPECT_EQ(parseCacheClock("counter"), CacheClock::Counter);
}

// The defaults a user of --cache texel / --cache tile gets: the best configuration measured
// on the H200 (docs/results.md, Table 6.1; the tiles' count in the wavefront): lru, the
// frame clock for texels and the counter clock for tiles (where the device has 64-bit buffer
// atomics), the update-counter read check, 2^24 texels or 2^21 4x4 tiles fitted to the
// device, and per policy a clock shift.
TEST(TexelCacheOptions, DefaultsAreTheBestMeasuredConfiguration) {
  CacheOptions options;
  EXPECT_EQ(options.eviction, CacheEviction::Lru);
  EXPECT_TRUE(options.updateCounter);
  EXPECT_EQ(options.valueFormat, CacheValueFormat::Fp32);
  EXPECT_FALSE(options.entries.has_value());
  EXPECT_EQ(defaultCacheEntries(CacheMode::Texel), 1u << 24);
  EXPECT_EQ(defaultCacheEntries(CacheMode::Tile), 1u << 21);
  // The clock: the frame clock for texels (faster at the same hit rate), the counter for
  // tiles where the device has 64-bit buffer atomics.
  CacheOptions texel = options, tile = options;
  texel.mode = CacheMode::Texel;
  tile.mode = CacheMode::Tile;
  EXPECT_EQ(cacheClockOf(texel, true), CacheClock::Frame);
  EXPECT_EQ(cacheClockOf(tile, true), CacheClock::Counter);
  EXPECT_EQ(cacheClockOf(tile, false), CacheClock::Frame);
  texel.clock = CacheClock::Counter;
  EXPECT_EQ(cacheClockOf(texel, true), CacheClock::Counter);  // a given clock is kept
  // Clock shift per policy: lru ticks on reads and writes (§5.3.3's bits 16..47), lrw only
  // on writes, so it keeps every bit.
  EXPECT_EQ(cacheClockShift(options), 16u);
  EXPECT_EQ(cacheClockShift(options, 1920ull * 1080 * 6 * 4), 16u);  // §5.3.3's 1080p choice
  EXPECT_EQ(cacheClockShift(options, 24 * 24 * 2), 0u);              // a test's tiny image
  options.eviction = CacheEviction::Lrw;
  EXPECT_EQ(cacheClockShift(options), 0u);
  options.clockShift = 5;
  EXPECT_EQ(cacheClockShift(options), 5u);
  CacheOptions lrw;
  lrw.mode = CacheMode::Texel;
  lrw.eviction = CacheEviction::Lrw;
  auto defines = cacheShaderDefines(lrw, 5);
  EXPECT_NE(std::find(defines.begin(), defines.end(), "MG_CACHE_CLOCK_COUNTER=1"), defines.end());
  EXPECT_NE(std::find(defines.begin(), defines.end(), "MG_CACHE_CLOCK_SHIFT=0"), defines.end());
  CacheOptions resolved = resolveCacheOptions(lrw, false);
  EXPECT_EQ(resolved.clock, CacheClock::Frame);
  EXPECT_EQ(resolved.clockShift, 0u);
}

// What a render with only the cache mode set reports on lavapipe: the frame clock (lru's
// default for texels, though lavapipe has 64-bit buffer atomics) and the texel count fitted below
// 2^24 (lavapipe's 128 MiB storage-buffer range holds 2^21 texel entries of 15 words).
TEST(TexelCacheOptions, DefaultTexelRenderUsesTheFrameClockAndFittedEntries) {
  RendererOptions options = testing::testOptions();
  options.cache.mode = CacheMode::Texel;
  Renderer renderer(options);
  RenderResult r = renderer.render(wallScene(stripesGraph(), false), settings(2, 1));
  std::printf("default texel cache on %s: %u entries, clock %s, eviction %s, check %s\n",
              renderer.context().info().name.c_str(), r.stats.cacheEntries,
              r.stats.cacheClock.c_str(), r.stats.cacheEviction.c_str(),
              r.stats.cacheReadCheck.c_str());
  EXPECT_EQ(r.stats.cacheClock, "frame");  // the texel cache's default under lru
  EXPECT_EQ(r.stats.cacheEviction, "lru");
  EXPECT_EQ(r.stats.cacheReadCheck, "counter");
  EXPECT_LE(r.stats.cacheEntries, 1u << 24);
  EXPECT_GT(r.stats.cacheEntries, 1u << 20);  // more than the old fixed default
  EXPECT_GT(r.stats.frames.back().cacheHits, 0u);
}

// §5.3.1: fp16 halves the value words and the picture stays close. Both renders snap uv, so
// which thread fills an entry does not matter (see the snapping test) and the difference is
// fp16 rounding alone. Bound: mean LDR-FLIP below 0.005 (the printed figure is the
// measurement).
TEST(TexelCacheOptions, Fp16EntriesAreSmallerAndRenderCloseToFp32) {
  Scene scene = wallScene(stripesGraph(), true);
  RendererOptions fullOptions = texelCache();
  fullOptions.cache.snapUv = true;
  RenderResult fp32 = Renderer(fullOptions).render(scene, settings(6, 3, 2));
  RendererOptions halfOptions = fullOptions;
  halfOptions.cache.valueFormat = CacheValueFormat::Fp16;
  RenderResult fp16 = Renderer(halfOptions).render(scene, settings(6, 3, 2));
  EXPECT_EQ(fp32.stats.cacheValueFormat, "fp32");
  EXPECT_EQ(fp16.stats.cacheValueFormat, "fp16");
  double flip = meanFlip(fp32.image, fp16.image);
  std::printf(
      "texel cache fp16 vs fp32: %llu B vs %llu B (%u values per entry), mean LDR-FLIP %.4f, "
      "last frame hit rates %.2f %% / %.2f %%\n",
      (unsigned long long)fp16.stats.cacheBytes, (unsigned long long)fp32.stats.cacheBytes,
      fp16.stats.cacheValueCount, flip, 100.0 * fp16.stats.frames.back().cacheHitRate(),
      100.0 * fp32.stats.frames.back().cacheHitRate());
  EXPECT_LT(fp16.stats.cacheBytes, fp32.stats.cacheBytes);
  EXPECT_GT(fp16.stats.frames.back().cacheHitRate(), 0.9);
  EXPECT_LT(flip, 0.005);
}

// §5.3.3's counter clock orders entries by access, across frames: lru with it holds its
// hit rate on a panning camera where `none` decays, as with the frame clock. Shift 0: the
// run makes about 20000 accesses, so bits 16.. (the thesis's 1080p choice) would all be 0.
TEST(TexelCacheOptions, CounterClockLruKeepsItsHitRateOnAPanningCamera) {
  Scene scene = testing::panningWallScene();
  RenderSettings panning = testing::panningSettings();
  double early[2], late[2];
  std::uint64_t lastTicks = 0;
  for (int i = 0; i < 2; ++i) {
    RendererOptions options = texelCache(1024, i == 0 ? CacheEviction::None : CacheEviction::Lru);
    options.cache.clock = CacheClock::Counter;
    options.cache.clockShift = 0;
    RenderResult r = Renderer(options).render(scene, panning);
    EXPECT_EQ(r.stats.cacheClock, "counter");
    early[i] = meanHitRate(r.stats, 1, 4);
    late[i] = meanHitRate(r.stats, panning.frames - 4, panning.frames);
    std::printf(
        "panning camera, 1024 entries, counter clock, eviction %s: hit rate frames 1-3 "
        "%.1f %%, last 4 frames %.1f %%; clock after the last frame %llu\n",
        cacheEvictionName(options.cache.eviction), 100.0 * early[i], 100.0 * late[i],
        (unsigned long long)r.stats.frames.back().cacheClockTicks);
    if (i == 1) {
      // Never reset: it grows every frame by that frame's lookups (each a hit or a write).
      for (std::size_t f = 1; f < r.stats.frames.size(); ++f)
        EXPECT_GT(r.stats.frames[f].cacheClockTicks, r.stats.frames[f - 1].cacheClockTicks);
      lastTicks = r.stats.frames.back().cacheClockTicks;
    }
  }
  EXPECT_GT(lastTicks, 32u * 24u * 24u / 2u);
  EXPECT_LT(late[0], early[0] - 0.2);   // none decays
  EXPECT_GT(late[1], early[1] - 0.05);  // lru holds
  EXPECT_GT(late[1], late[0] + 0.2);
}

// §6.1 snapping: a miss evaluates the graph at its texel's centre, so every thread that
// fills an entry writes the same value and the picture no longer depends on which thread
// came first: two renders are identical. The hit rate is that of the unsnapped cache.
TEST(TexelCacheOptions, SnappedUvKeepsTheHitRateAndMakesRendersRepeatable) {
  Scene scene = wallScene(stripesGraph(), false);
  RenderResult off = Renderer(noCache()).render(scene, settings(8, 1));
  RendererOptions options = texelCache();
  options.cache.snapUv = true;
  RenderResult a = Renderer(options).render(scene, settings(8, 1));
  RenderResult b = Renderer(options).render(scene, settings(8, 1));
  RenderResult unsnapped = Renderer(texelCache()).render(scene, settings(8, 1));
  EXPECT_TRUE(a.stats.cacheSnapUv);
  double maxAbs = 0.0;
  for (std::size_t i = 0; i < a.image.rgba.size(); ++i)
    maxAbs = std::max(maxAbs, double(std::fabs(a.image.rgba[i] - b.image.rgba[i])));
  std::printf(
      "texel cache, snapped uv: last frame hit rate %.2f %% (unsnapped %.2f %%), mean "
      "LDR-FLIP vs none %.4f (unsnapped %.4f), two snapped renders differ by at most %g\n",
      100.0 * a.stats.frames.back().cacheHitRate(),
      100.0 * unsnapped.stats.frames.back().cacheHitRate(), meanFlip(off.image, a.image),
      meanFlip(off.image, unsnapped.image), maxAbs);
  EXPECT_GT(a.stats.frames.back().cacheHitRate(), 0.99);
  EXPECT_LT(meanFlip(off.image, a.image), 0.06);
  EXPECT_EQ(maxAbs, 0.0);
}

// Snapping evaluates a texel with the fictional derivatives of one texel (eq. 5.16-5.17, as
// the tile cache does), not the derivatives of whichever hit missed first: a graph whose value
// depends on its footprint (an image texture's mip level) then stores the same value whoever
// fills the entry, and two renders are bitwise identical. The texture's levels differ (red =
// level), the wall is seen at a slant so neighbouring hits of one texel have different
// footprints, and the image is rendered twice with 8 frames each.
TEST(TexelCacheOptions, SnappedTexelsUseTheTexelsFootprint) {
  constexpr int kLevels = 7;
  RendererOptions options = texelCache();
  options.cache.snapUv = true;
  options.textureLoader = [](const std::string&) {
    return testing::levelTaggedChecker(64, kLevels, 2);
  };
  Scene scene = wallScene(
      "material Levels;\nUVInput UV>0;\nImageTexture Image=\"levels.pfm\" "
      "UV<0 Color>1;\nBaseColorOutput Color<1;\n",
      false);
  scene.camera.position = {-5.0f, 1.0f, 3.0f};  // a slant view of the wall
  std::vector<RenderResult> renders;
  for (int i = 0; i < 2; ++i)
    renders.push_back(Renderer(options).render(scene, settings(8, 2)));
  const auto& a = renders[0].image.rgba;
  const auto& b = renders[1].image.rgba;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    differing += a[i] != b[i];
  std::printf(
      "snapped image texture at a slant: %zu of %zu floats differ between two renders, "
      "last frame hit rate %.2f %%\n",
      differing, a.size(), 100.0 * renders[0].stats.frames.back().cacheHitRate());
  EXPECT_GT(renders[0].stats.frames.back().cacheHitRate(), 0.9);
  EXPECT_EQ(differing, 0u);
}

// §6.1, Fig. 6.6: the cache's error comes almost all from primary hits, so caching only
// bounces >= 1 is closer to the uncached picture than caching every hit. Enough paths
// (32x32, P = 4, 8 frames) that the comparison is not noise: the renders share the seed,
// so the remaining differences are the cache's.
TEST(TexelCacheOptions, SecondaryOnlyCachingIsCloserToUncachedThanFullCaching) {
  Scene scene = wallScene(stripesGraph(), true);
  RenderSettings s = settings(8, 3, 4, 32);
  RenderResult off = Renderer(noCache()).render(scene, s);
  RenderResult full = Renderer(texelCache()).render(scene, s);
  RendererOptions secondaryOptions = texelCache();
  secondaryOptions.cache.secondaryOnly = true;
  RenderResult secondary = Renderer(secondaryOptions).render(scene, s);
  double flipFull = meanFlip(off.image, full.image);
  double flipSecondary = meanFlip(off.image, secondary.image);
  const FrameStats& lastFull = full.stats.frames.back();
  const FrameStats& lastSecondary = secondary.stats.frames.back();
  std::printf(
      "mean LDR-FLIP vs no cache: every hit cached %.4f (%llu lookups, %.2f %% hits), "
      "secondary hits only %.4f (%llu lookups, %.2f %% hits)\n",
      flipFull, (unsigned long long)lastFull.cacheLookups, 100.0 * lastFull.cacheHitRate(),
      flipSecondary, (unsigned long long)lastSecondary.cacheLookups,
      100.0 * lastSecondary.cacheHitRate());
  EXPECT_TRUE(secondary.stats.cacheSecondaryOnly);
  EXPECT_GT(lastSecondary.cacheLookups, 0u);
  EXPECT_LT(lastSecondary.cacheLookups, lastFull.cacheLookups);
  EXPECT_LT(flipSecondary, flipFull);
}

// Occupancy: entries ever filled, kept across frames. On a static camera it only grows
// and stays within S (a 9-entry cache with D = 8 reaches 8: I = H0 mod (S - D) is 0, eq.
// 5.10). The tile counters stay 0.
TEST(TexelCacheOptions, OccupancyGrowsMonotonicallyWithinTheEntryCount) {
  Scene scene = wallScene(stripesGraph(), true);
  for (std::uint32_t entries : {1u << 16, 9u}) {
    RenderResult r = Renderer(texelCache(entries)).render(scene, settings(6, 2));
    std::printf("texel cache of %u entries, static camera: occupancy per frame", entries);
    for (const FrameStats& f : r.stats.frames)
      std::printf(" %llu", (unsigned long long)f.cacheOccupancy);
    std::printf("\n");
    for (std::size_t f = 0; f < r.stats.frames.size(); ++f) {
      const FrameStats& frame = r.stats.frames[f];
      EXPECT_LE(frame.cacheOccupancy, entries);
      EXPECT_EQ(frame.cacheTilesComputed, 0u);
      EXPECT_EQ(frame.cacheDuplicateTiles, 0u);
      if (f > 0) {
        EXPECT_GE(frame.cacheOccupancy, r.stats.frames[f - 1].cacheOccupancy);
      }
    }
    EXPECT_GT(r.stats.frames.front().cacheOccupancy, 0u);
    // Frame 0 misses fill entries: at least one per distinct missed texel, up to S.
    EXPECT_LE(r.stats.frames.front().cacheOccupancy, r.stats.frames.front().cacheMisses);
  }
  RenderResult none = Renderer(noCache()).render(scene, settings(1, 1));
  EXPECT_EQ(none.stats.frames.back().cacheOccupancy, 0u);
}

// Fig. 6.9's miss view: a cold cache's first frame is mostly red; after a static camera
// has warmed the cache (primary hits only), nearly no pixel misses.
TEST(TexelCacheOptions, DebugViewPaintsMissesRed) {
  Scene scene = wallScene(stripesGraph(), false);
  RendererOptions options = texelCache();
  options.debugCacheMisses = true;
  RenderResult cold = Renderer(options).render(scene, settings(1, 1));
  RenderResult warm = Renderer(options).render(scene, settings(10, 1));
  RenderResult plain = Renderer(texelCache()).render(scene, settings(10, 1));
  const std::size_t pixels = 24 * 24;
  std::printf(
      "miss view: frame 0 of a cold cache %zu of %zu pixels red (%llu misses); frame 9 %zu "
      "red (%llu misses); normal view %zu red\n",
      redPixels(cold.image), pixels, (unsigned long long)cold.stats.frames.back().cacheMisses,
      redPixels(warm.image), (unsigned long long)warm.stats.frames.back().cacheMisses,
      redPixels(plain.image));
  EXPECT_GT(redPixels(cold.image), pixels / 2);
  EXPECT_EQ(redPixels(cold.image), cold.stats.frames.back().cacheMisses);  // L = 1, P = 1
  EXPECT_LE(redPixels(warm.image), pixels / 100);
  EXPECT_EQ(redPixels(plain.image), 0u);
  options.cache.mode = CacheMode::None;
  EXPECT_THROW(Renderer(options).render(scene, settings(1, 1)), std::invalid_argument);
}

// The floor run evaluates no graph: no cache lookup, a picture of per-material constants
// that differs from the real materials, on both dispatches. With a cache it measures the
// cache's own cost (docs/results.md): the same lookups and hits, and the constants come
// back out of the cache, so the picture is the uncached floor's.
TEST(TexelCacheOptions, FloorRunReplacesEveryMaterialByConstants) {
  Scene scene = wallScene(stripesGraph(), true);
  RenderResult real = Renderer(noCache()).render(scene, settings(2, 2));
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    RendererOptions options = testing::testOptions(backend);
    options.floorMaterials = true;
    RenderResult floor = Renderer(options).render(scene, settings(2, 2));
    double flip = meanFlip(real.image, floor.image);
    std::printf("floor run (%s backend): dispatch %s, mean LDR-FLIP vs the real materials %.4f\n",
                floor.stats.backend.c_str(), floor.stats.materialDispatch.c_str(), flip);
    EXPECT_EQ(floor.stats.materialDispatch, "floor");
    for (const FrameStats& f : floor.stats.frames)
      EXPECT_EQ(f.cacheLookups, 0u);
    for (float value : floor.image.rgba)
      ASSERT_TRUE(std::isfinite(value));
    EXPECT_GT(flip, 0.05);
  }
  RendererOptions plain = testing::testOptions(Backend::RayQuery);
  plain.floorMaterials = true;
  RenderResult floor = Renderer(plain).render(scene, settings(3, 2));
  RendererOptions cached = texelCache();
  cached.floorMaterials = true;
  RenderResult floorCached = Renderer(cached).render(scene, settings(3, 2));
  testing::expectConsistentCounters(floorCached.stats);
  EXPECT_EQ(floorCached.stats.materialDispatch, "floor");
  EXPECT_GT(floorCached.stats.frames.front().cacheLookups, 0u);
  EXPECT_GT(floorCached.stats.frames.back().cacheHitRate(), 0.8);  // frame 2, cold cache: 0.91
  double flip = meanFlip(floor.image, floorCached.image);
  std::printf("floor run with the texel cache: mean LDR-FLIP %.5f vs the floor without\n", flip);
  EXPECT_LT(flip, 0.001);
}

}  // namespace
}  // namespace memograph::runtime
