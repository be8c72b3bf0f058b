// The texel cache (thesis §4.2-4.5, §5.3) on lavapipe: a static camera's image with the
// cache stays close to the uncached one (LDR-FLIP), its hit rate climbs above 99 %, a
// per-hit material (neither cacheable nor with a cut) never touches the cache, and a cache
// far too small for the scene still renders (probe ranges full, writes dropped) without
// hanging; the behavioural ones in both architectures (megakernel and wavefront).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/shaders/shared_types.h"
#include "texel_cache_scenes.h"
#include "tools/quality/flip.h"

namespace memograph::runtime {
namespace {

using testing::cacheOptions;
using testing::expectConsistentCounters;
using testing::meanFlip;
using testing::perHitGraph;
using testing::stripesGraph;
using testing::wallScene;

RenderSettings settings(std::uint32_t frames, std::uint32_t raysPerPath, std::uint32_t paths = 1) {
  return testing::cacheSettings(frames, raysPerPath, paths);
}

TEST(TexelCache, OutputMaskFollowsTheWrittenOutputs) {
  std::uint32_t floats = 0;
  EXPECT_EQ(cacheOutputMask({"baseColor", "roughness"}, &floats),
            gpu::kCacheOutputBaseColor | gpu::kCacheOutputRoughness);
  EXPECT_EQ(floats, 4u);
  EXPECT_EQ(cacheOutputMask({"baseColor", "metallic", "roughness", "normal", "emission", "opacity"},
                            &floats),
            63u);
  EXPECT_EQ(floats, 12u);
  EXPECT_EQ(cacheOutputMask({"specular", "specularTint", "cyclesPrincipled"}, &floats),
            gpu::kCacheOutputSpecular | gpu::kCacheOutputSpecularTint |
                gpu::kCacheOutputCyclesPrincipled);
  EXPECT_EQ(floats, 3u);
  EXPECT_THROW(cacheOutputMask({"sheen"}), std::runtime_error);
}

// Specular Tint and the Cycles weighting (docs/design/material-interface.md) are outputs like the
// others: both cache kinds store and restore them. A glossy red wall (Specular 1: F0 0.08)
// under a grey sky and a point light, its outputs constant, so a cached entry holds
// exactly the graph's values and the cached image is the uncached one. Tinted, the
// wall's reflection loses green (F0 0.012 in green), so a cache that dropped the two
// outputs (restoring the defaults, 0) would render the untinted wall. Bounds: each
// cache's mean red and green within 1 % of the uncached render's; the untinted wall's
// green at least 20 % above the tinted one's (measured on lavapipe: both caches equal to
// the uncached red 0.6152 and green 0.0310; untinted red 0.4876, green 0.0677).
TEST(TexelCache, SpecularTintAndCyclesWeightingSurviveBothCacheKinds) {
  auto wallGraph = [](bool tinted) {
    std::string g =
        "material Glossy;\nBaseColorOutput Color=(1, 0.05, 0.05);\n"
        "RoughnessOutput Roughness=0.3;\nSpecularOutput In=1;\n";
    if (tinted)
      g += "SpecularTintOutput In=1;\nCyclesPrincipledOutput In=1;\n";
    return g;
  };
  auto channelMean = [](const RenderResult& r, int c) {
    return testing::meanChannel(r.image, c, 0, 0, int(r.image.width), int(r.image.height));
  };
  RendererOptions tile = cacheOptions(CacheMode::Tile, Backend::RayQuery);
  tile.cache.tileWidth = 2;
  tile.cache.tileHeight = 2;
  const Scene tinted = wallScene(wallGraph(true), false);
  const RenderResult none =
      Renderer(cacheOptions(CacheMode::None, Backend::RayQuery)).render(tinted, settings(4, 2, 2));
  const RenderResult plain = Renderer(cacheOptions(CacheMode::None, Backend::RayQuery))
                                 .render(wallScene(wallGraph(false), false), settings(4, 2, 2));
  const double red = channelMean(none, 0), green = channelMean(none, 1);
  std::printf("tinted wall, uncached: mean red %.4f green %.4f; untinted: red %.4f green %.4f\n",
              red, green, channelMean(plain, 0), channelMean(plain, 1));
  EXPECT_GT(channelMean(plain, 1), 1.2 * green);
  for (const RendererOptions& options : {cacheOptions(CacheMode::Texel, Backend::RayQuery), tile}) {
    const RenderResult cached = Renderer(options).render(tinted, settings(4, 2, 2));
    expectConsistentCounters(cached.stats);
    std::printf("tinted wall, %s cache: mean red %.4f green %.4f, last frame hit rate %.2f %%\n",
                cached.stats.cache.c_str(), channelMean(cached, 0), channelMean(cached, 1),
                100.0 * cached.stats.frames.back().cacheHitRate());
    EXPECT_GT(cached.stats.frames.back().cacheLookups, 0u) << cached.stats.cache;
    EXPECT_NEAR(channelMean(cached, 0), red, 0.01 * red) << cached.stats.cache;
    EXPECT_NEAR(channelMean(cached, 1), green, 0.01 * green) << cached.stats.cache;
  }
}

// The texel cache in both architectures: the megakernel, and the wavefront's lookup pass and
// material passes (--shading wavefront), whose inserts come after all lookups of a bounce.
class TexelCacheInBothArchitectures : public ::testing::TestWithParam<Shading> {
 protected:
  RendererOptions options(CacheMode mode, Backend backend = Backend::Auto,
                          std::optional<std::uint32_t> entries = 1u << 16,
                          CacheEviction eviction = CacheEviction::Lru) const {
    RendererOptions o = cacheOptions(mode, backend, entries, eviction);
    o.shading = GetParam();
    return o;
  }
};

TEST_P(TexelCacheInBothArchitectures, StaticCameraHitRateExceeds99PercentAfterAFewFrames) {
  Scene scene = wallScene(stripesGraph(), false);
  Renderer renderer(options(CacheMode::Texel));
  RenderResult result = renderer.render(scene, settings(12, 1));
  expectConsistentCounters(result.stats);
  const FrameStats& first = result.stats.frames.front();
  const FrameStats& last = result.stats.frames.back();
  std::printf(
      "texel cache, static camera, primary hits: frame 0 hit rate %.2f %%, frame %u "
      "hit rate %.2f %% (%llu lookups)\n",
      100.0 * first.cacheHitRate(), last.frame, 100.0 * last.cacheHitRate(),
      (unsigned long long)last.cacheLookups);
  EXPECT_EQ(last.cacheLookups, 24u * 24u);  // one cacheable primary hit per pixel
  EXPECT_GT(last.cacheHitRate(), 0.99);
}

// §5.1's shared primary ray: the P paths of a pixel share one camera ray, so the megakernel
// evaluates or looks up its hit's material once, not P times: one lookup a pixel at L = 1,
// where P = 4 paths without the shared ray make four.
TEST(TexelCache, SharedPrimaryRayMakesOneLookupAPixel) {
  Scene scene = wallScene(stripesGraph(), false);
  RenderSettings s = settings(3, 1, 4);
  s.sharedPrimaryRay = true;
  RenderResult shared = Renderer(cacheOptions(CacheMode::Texel)).render(scene, s);
  expectConsistentCounters(shared.stats);
  RenderSettings jittered = settings(3, 1, 4);
  RenderResult own = Renderer(cacheOptions(CacheMode::Texel)).render(scene, jittered);
  const FrameStats& last = shared.stats.frames.back();
  std::printf("shared primary ray, P = 4: %llu lookups a frame (own rays: %llu)\n",
              (unsigned long long)last.cacheLookups,
              (unsigned long long)own.stats.frames.back().cacheLookups);
  EXPECT_EQ(last.cacheLookups, 24u * 24u);
  EXPECT_EQ(own.stats.frames.back().cacheLookups, 4u * 24u * 24u);
  EXPECT_GT(last.cacheHitRate(), 0.99);
}

// Cache on against off: the cached outputs are the graph's at another point of the same
// texel (nearest filtering, §4.3), so images differ slightly; the texels are one ray-cone
// footprint wide, so the stripes are quantized like a nearest-filtered texture of about one
// texel per pixel. Bound: mean LDR-FLIP below 0.06 (measured on lavapipe: 0.041 query,
// 0.043 callables; the printed figure).
void expectCloseToUncached(Backend backend, bool updateCounter = true,
                           Shading shading = Shading::Megakernel) {
  Scene scene = wallScene(stripesGraph(), true);
  RendererOptions offOptions = cacheOptions(CacheMode::None, backend);
  offOptions.shading = shading;
  RenderResult off = Renderer(offOptions).render(scene, settings(6, 3, 2));
  RendererOptions onOptions = cacheOptions(CacheMode::Texel, backend);
  onOptions.shading = shading;
  onOptions.cache.updateCounter = updateCounter;
  RenderResult on = Renderer(onOptions).render(scene, settings(6, 3, 2));
  EXPECT_EQ(on.stats.cacheReadCheck, updateCounter ? "counter" : "key");
  expectConsistentCounters(on.stats);
  for (const FrameStats& f : off.stats.frames)
    EXPECT_EQ(f.cacheLookups, 0u);
  double flip = meanFlip(off.image, on.image);
  std::printf(
      "texel cache (read check %s) vs none (%s backend, %s, %s): mean LDR-FLIP %.4f, last "
      "frame hit rate %.2f %%\n",
      on.stats.cacheReadCheck.c_str(), on.stats.backend.c_str(), on.stats.materialDispatch.c_str(),
      on.stats.shading.c_str(), flip, 100.0 * on.stats.frames.back().cacheHitRate());
  EXPECT_GT(on.stats.frames.back().cacheLookups, 0u);
  EXPECT_LT(flip, 0.06);
}

TEST(TexelCache, CachedImageIsCloseToUncachedOnTheQueryBackend) {
  expectCloseToUncached(Backend::RayQuery);
}

TEST(TexelCache, CachedImageIsCloseToUncachedWithCallables) {
  expectCloseToUncached(Backend::RayTracingPipeline);
}

// The thesis's key read check (key, values, key) renders like the update counter, the
// default. (That the counter closes the A-B-A race: TexelCacheStress.)
TEST(TexelCache, CachedImageIsCloseToUncachedInTheWavefront) {
  expectCloseToUncached(Backend::RayQuery, true, Shading::Wavefront);
}

TEST(TexelCache, KeyReadCheckRendersLikeTheUpdateCounter) {
  expectCloseToUncached(Backend::RayQuery, false);
}

// Eq. 5.5's bias: +1 halves the texels (finer, closer to the uncached image, fewer hits),
// -1 doubles them (coarser, more hits).
TEST(TexelCache, MipBiasTradesHitRateForFidelity) {
  Scene scene = wallScene(stripesGraph(), false);
  RenderResult off = Renderer(cacheOptions(CacheMode::None)).render(scene, settings(6, 1));
  double flip[3], hitRate[3];
  for (int i = 0; i < 3; ++i) {
    RendererOptions options = cacheOptions(CacheMode::Texel);
    options.cache.mipBias = float(i - 1);
    RenderResult on = Renderer(options).render(scene, settings(6, 1));
    flip[i] = meanFlip(off.image, on.image);
    hitRate[i] = on.stats.frames.back().cacheHitRate();
    std::printf("texel cache, mip bias %+d: mean LDR-FLIP %.4f, last frame hit rate %.2f %%\n",
                i - 1, flip[i], 100.0 * hitRate[i]);
  }
  EXPECT_GT(flip[0], flip[1]);
  EXPECT_GT(flip[1], flip[2]);
  EXPECT_GE(hitRate[0], hitRate[1]);
  EXPECT_GT(hitRate[1], hitRate[2]);
}

TEST_P(TexelCacheInBothArchitectures, NonCacheableMaterialNeverTouchesTheCache) {
  Scene scene = wallScene(perHitGraph(), false);
  RenderResult off = Renderer(options(CacheMode::None)).render(scene, settings(3, 2));
  RenderResult on = Renderer(options(CacheMode::Texel)).render(scene, settings(3, 2));
  for (const FrameStats& f : on.stats.frames) {
    EXPECT_EQ(f.cacheLookups, 0u) << "frame " << f.frame;
    EXPECT_EQ(f.cacheHits, 0u);
    EXPECT_EQ(f.cacheMisses, 0u);
  }
  // Evaluated directly, as without the cache: the same image.
  double maxAbs = 0.0;
  for (std::size_t i = 0; i < off.image.rgba.size(); ++i)
    maxAbs = std::max(maxAbs, double(std::fabs(off.image.rgba[i] - on.image.rgba[i])));
  EXPECT_LE(maxAbs, 1e-6);
}

TEST_P(TexelCacheInBothArchitectures, FarTooFewEntriesStillRenders) {
  Scene scene = wallScene(stripesGraph(), true);
  RenderResult off = Renderer(options(CacheMode::None)).render(scene, settings(3, 3));
  for (CacheEviction eviction :
       {CacheEviction::None, CacheEviction::Lru, CacheEviction::Lrw, CacheEviction::Random}) {
    // S = D + 1: one probe range, nine entries for hundreds of texels.
    RenderResult on = Renderer(options(CacheMode::Texel, Backend::Auto, 9, eviction))
                          .render(scene, settings(3, 3));
    expectConsistentCounters(on.stats);
    for (float value : on.image.rgba)
      ASSERT_TRUE(std::isfinite(value));
    const FrameStats& last = on.stats.frames.back();
    double flip = meanFlip(off.image, on.image);
    std::printf(
        "texel cache of 9 entries (eviction %s): last frame %llu lookups, hit rate "
        "%.2f %%, mean LDR-FLIP vs none %.4f\n",
        cacheEvictionName(eviction), (unsigned long long)last.cacheLookups,
        100.0 * last.cacheHitRate(), flip);
    EXPECT_GT(last.cacheLookups, 0u);
    EXPECT_LT(last.cacheHitRate(), 0.5);
    EXPECT_LT(flip, 0.05);
  }
}

// Thesis Fig. 6.14's trend: a camera panning along a long wall with a cache of a few frames'
// texels. Without eviction the hit rate falls once the cache is full (new texels find no
// empty entry); with lru it stays high (consecutive frames overlap).
TEST_P(TexelCacheInBothArchitectures, PanningCameraKeepsItsHitRateOnlyWithEviction) {
  Scene scene = testing::panningWallScene();
  RenderSettings s = testing::panningSettings();
  double early[2], late[2];
  for (int i = 0; i < 2; ++i) {
    CacheEviction eviction = i == 0 ? CacheEviction::None : CacheEviction::Lru;
    RenderResult r =
        Renderer(options(CacheMode::Texel, Backend::Auto, 1024, eviction)).render(scene, s);
    expectConsistentCounters(r.stats);
    auto mean = [&](std::size_t from, std::size_t to) {
      double sum = 0;
      for (std::size_t f = from; f < to; ++f)
        sum += r.stats.frames[f].cacheHitRate();
      return sum / double(to - from);
    };
    early[i] = mean(1, 4);
    late[i] = mean(s.frames - 4, s.frames);
    std::printf(
        "panning camera, 1024 entries, eviction %s: hit rate frames 1-3 %.1f %%, last 4 "
        "frames %.1f %%\n",
        cacheEvictionName(eviction), 100.0 * early[i], 100.0 * late[i]);
  }
  EXPECT_LT(late[0], early[0] - 0.2);   // none decays
  EXPECT_GT(late[1], early[1] - 0.05);  // lru holds
  EXPECT_GT(late[1], late[0] + 0.2);
}

TEST(TexelCache, StatsCsvAppendsTheCacheColumns) {
  RenderStats stats;
  stats.cache = "texel";
  stats.cacheEviction = "lru";
  stats.cacheEntries = 1024;
  stats.cacheReadCheck = "key";
  FrameStats frame;
  frame.cacheLookups = 200;
  frame.cacheHits = 150;
  frame.cacheMisses = 50;
  stats.frames.push_back(frame);
  std::ostringstream csv;
  writeStatsCsv(csv, stats);
  std::string text = csv.str();
  std::string header = text.substr(0, text.find('\n'));
  std::string row = text.substr(header.size() + 1);
  // Appended after the columns that were there before the cache.
  EXPECT_NE(
      header.find(
          "pipeline_create_ms,cache,cache_eviction,cache_entries,cache_probe,"
          "cache_bytes,cache_lookups,cache_hits,cache_misses,cache_hit_rate,cache_read_check"),
      std::string::npos);
  EXPECT_NE(row.find(",texel,lru,1024,0,0,200,150,50,0.75,key,"), std::string::npos) << row;
}

TEST(TexelCache, BadOptionsAreRefused) {
  Scene scene = wallScene(stripesGraph(), false);
  for (auto [entries, probe] : {std::pair{8u, 8u}, std::pair{100u, 0u}, std::pair{100u, 17u}}) {
    RendererOptions options = cacheOptions(CacheMode::Texel, Backend::Auto, entries);
    options.cache.probe = probe;
    EXPECT_THROW(Renderer(options).render(scene, settings(1, 1)), std::invalid_argument)
        << entries << " entries, probe " << probe;
  }
  // More entries than one allocation of the device holds (lavapipe: 2 GiB; 2^31 entries of
  // at least 12 bytes exceed any device's) is refused before allocating, naming the option
  // (lavapipe crashed in vkAllocateMemory before this check).
  Renderer huge(cacheOptions(CacheMode::Texel, Backend::Auto, 1u << 31));
  try {
    huge.render(scene, settings(1, 1));
    ADD_FAILURE() << "a cache of 2^31 entries was allocated";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--cache-entries 2147483648"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parseCacheMode("tiles"), std::invalid_argument);
  EXPECT_THROW(parseCacheEviction("fifo"), std::invalid_argument);
  EXPECT_EQ(parseCacheEviction("lrw"), CacheEviction::Lrw);
  EXPECT_EQ(parseCacheEviction("random"), CacheEviction::Random);
}

// The default entry count (CacheOptions::entries unset) is halved until the cache fits one
// storage-buffer binding of the device (binding more is invalid usage that lavapipe does not
// catch: its range is 128 MiB, less than the landscape's default 4x2 tile cache); a given
// count that does not fit is refused, naming the option. 64x64 tiles (deferred fill) need
// at least 48 KiB an entry, so 2^20 of them fit no device's binding.
TEST(TexelCache, DefaultEntriesFitTheStorageBufferRange) {
  Scene scene = wallScene(stripesGraph(), false);
  RendererOptions options = cacheOptions(CacheMode::Tile, Backend::RayQuery, std::nullopt);
  options.cache.tileWidth = options.cache.tileHeight = 64;
  options.cache.tileFill = TileFill::Deferred;
  options.cache.tileQueue = 64;
  Renderer fitted(options);
  const DeviceInfo& info = fitted.context().info();
  const std::uint64_t range = info.limits.maxStorageBufferRange;
  RenderResult result = fitted.render(scene, settings(2, 1));
  const std::uint64_t queueBytes = sizeof(gpu::TileQueueHeader) + 64 * sizeof(gpu::TileFillItem);
  const std::uint64_t entryBytes = result.stats.cacheBytes - queueBytes;
  std::printf("default tile cache of 64x64 texels: %u entries, %llu bytes (range %llu)\n",
              result.stats.cacheEntries, (unsigned long long)entryBytes, (unsigned long long)range);
  EXPECT_TRUE(result.stats.cacheEntriesFitted);
  EXPECT_LT(result.stats.cacheEntries, kDefaultCacheEntries);
  EXPECT_LE(entryBytes, range);
  EXPECT_GT(2 * entryBytes, range);  // halved no further than needed
  EXPECT_GT(result.stats.frames.back().cacheHits, 0u);

  options.cache.entries = kDefaultCacheEntries;
  try {
    Renderer(options).render(scene, settings(1, 1));
    ADD_FAILURE() << kDefaultCacheEntries << " tiles of 64x64 texels were bound";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--cache-entries " + std::to_string(kDefaultCacheEntries)),
              std::string::npos)
        << e.what();
  }
  // A texel cache one entry (at least 16 bytes) past the range: where the range is smaller
  // than the largest allocation (lavapipe), the range is what refuses it.
  const auto entries = static_cast<std::uint32_t>(range / 16 + 1);
  try {
    Renderer(cacheOptions(CacheMode::Texel, Backend::RayQuery, entries))
        .render(scene, settings(1, 1));
    ADD_FAILURE() << entries << " texel entries were bound";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--cache-entries " + std::to_string(entries)),
              std::string::npos)
        << e.what();
    if (range < info.maxMemoryAllocationSize) {
      EXPECT_NE(std::string(e.what()).find("storage-buffer range"), std::string::npos) << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, TexelCacheInBothArchitectures,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

}  // namespace
}  // namespace memograph::runtime
