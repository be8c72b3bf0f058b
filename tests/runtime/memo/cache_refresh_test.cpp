// The texel cache's refresh (CacheOptions::refreshFrames, `--cache-refresh`; texel_cache.glsl
// cacheKeyOfHashes; docs/design/memoization.md, "Refresh"). A cut's entry is evaluated at one
// point of its cell, so a material that varies inside the cell is held at that one value for
// as long as the entry stays: accumulated frames converge to the cell's point sample, not to
// what the uncached render sees, which is the cached picture's bias. With a refresh every N
// frames each key is filled again at another point of its cell, so the accumulated frames
// average the cell instead.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/materials/material_linker.h"
#include "runtime/memo/cache_options.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/shading.h"
#include "texel_cache_scenes.h"

namespace memograph::runtime {
namespace {

// Stripes of the world x, 1/23.7 m apart (about a fifth of a pixel here), kept by a Layer
// Weight mix (per hit) so the stripes are a world-space cut: every cell of the cache holds many
// stripes, and its centre's value is anything in [0, 1) while the stripes average 1/2.
const char* kWorldStripesGraph =
    "material WorldStripes;\n"
    "PositionInput Out>1;\n"
    "Separate3 Vector<1 X>2 Y>3 Z>4;\n"
    "Mul A<2 B=23.7 Out>5;\n"
    "Fract In<5 Out>6;\n"
    "Combine3 X<6 Y<6 Z<6 Vector>7;\n"
    "LayerWeight Facing>8;\n"
    "MixColor Factor<8 A<7 B=(0.0, 0.0, 0.0) Result>9;\n"
    "BaseColorOutput In<9;\n";

// Cells 8 footprints wide (mip bias -3), as the filters' ramps.
RendererOptions options(CacheMode mode, Shading shading, std::uint32_t refreshFrames) {
  RendererOptions o = testing::cacheOptions(mode, Backend::RayQuery);
  o.nodeLibraryDirectory.clear();  // the embedded (real) node library
  o.shading = shading;
  o.cache.mipBias = -3.0f;
  o.cache.refreshFrames = refreshFrames;
  return o;
}

RenderSettings settings(std::uint32_t frames) {
  return testing::primaryHitSettings(frames);
}

// The results page's bias measure at this size: the mean absolute difference of 4x4-block
// means (all three colour channels).
double blockMeanAbsoluteError(const HdrImage& a, const HdrImage& b) {
  double sum = 0.0;
  int blocks = 0;
  for (int by = 0; by + 4 <= int(a.height); by += 4)
    for (int bx = 0; bx + 4 <= int(a.width); bx += 4)
      for (int c = 0; c < 3; ++c) {
        sum += std::abs(testing::meanChannel(a, c, bx, by, bx + 4, by + 4) -
                        testing::meanChannel(b, c, bx, by, bx + 4, by + 4));
        ++blocks;
      }
  return blocks > 0 ? sum / blocks : 0.0;
}

class CacheRefresh : public ::testing::TestWithParam<Shading> {};

// 64 frames of a still camera each: uncached; cached without refresh; cached with every key
// refreshed each frame (N = 1) and every 4th frame (N = 4). Measured on lavapipe, the same in
// the megakernel and the wavefront: block error against uncached 0.0330 without refresh
// (hit rate 100 %), 0.0034 with N = 1 (87.9 %), 0.0087 with N = 4 (96.3 %). Bounds: the held
// values' error above 0.02 (the bias the refresh is for), N = 1 below a third of it, N = 4
// below a half, and the refresh costs hits.
TEST_P(CacheRefresh, AccumulatedFramesAverageTheCellInsteadOfHoldingOnePoint) {
  const LinkedMaterial m = linkMaterials({{"M", "", kWorldStripesGraph}}).materials.at(0);
  ASSERT_EQ(m.cutDomain, gpu::kCacheCutWorld) << "the stripes are a world-space cut";
  const Scene scene = testing::wallScene(kWorldStripesGraph, false);
  const Shading shading = GetParam();
  const RenderResult off =
      Renderer(options(CacheMode::None, shading, 0)).render(scene, settings(64));
  const RenderResult held =
      Renderer(options(CacheMode::Texel, shading, 0)).render(scene, settings(64));
  const RenderResult everyFrame =
      Renderer(options(CacheMode::Texel, shading, 1)).render(scene, settings(64));
  const RenderResult everyFourth =
      Renderer(options(CacheMode::Texel, shading, 4)).render(scene, settings(64));
  testing::expectConsistentCounters(everyFrame.stats);
  testing::expectConsistentCounters(everyFourth.stats);
  const double errorHeld = blockMeanAbsoluteError(held.image, off.image);
  const double errorEveryFrame = blockMeanAbsoluteError(everyFrame.image, off.image);
  const double errorEveryFourth = blockMeanAbsoluteError(everyFourth.image, off.image);
  std::printf(
      "%s: 4x4-block error against uncached after 64 frames: no refresh %.4f (hit rate %.2f "
      "%%), refresh 1 %.4f (%.2f %%), refresh 4 %.4f (%.2f %%)\n",
      shadingName(shading), errorHeld, 100.0 * held.stats.frames.back().cacheHitRate(),
      errorEveryFrame, 100.0 * everyFrame.stats.frames.back().cacheHitRate(), errorEveryFourth,
      100.0 * everyFourth.stats.frames.back().cacheHitRate());
  EXPECT_GT(errorHeld, 0.02) << "the held cell values are the bias to remove";
  EXPECT_LT(errorEveryFrame, errorHeld / 3.0);
  EXPECT_LT(errorEveryFourth, errorHeld / 2.0);
  EXPECT_GT(held.stats.frames.back().cacheHitRate(), everyFrame.stats.frames.back().cacheHitRate());
}

// A refreshed key is still a function of the key and the frame: two renders at one seed are
// the same image, bit for bit.
TEST_P(CacheRefresh, RendersRepeatPerSeed) {
  const Scene scene = testing::wallScene(kWorldStripesGraph, false);
  const RenderResult a =
      Renderer(options(CacheMode::Texel, GetParam(), 2)).render(scene, settings(6));
  const RenderResult b =
      Renderer(options(CacheMode::Texel, GetParam(), 2)).render(scene, settings(6));
  EXPECT_EQ(a.image.rgba, b.image.rgba);
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, CacheRefresh,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

// The refresh moves an entry's evaluation point inside its cell, which the filters' blend (by
// the cells' centres) and the tile cache (texels at their centres) do not allow.
TEST(CacheRefreshOptions, TheTileCacheAndTheFiltersRefuseIt) {
  CacheOptions tile;
  tile.mode = CacheMode::Tile;
  tile.refreshFrames = 4;
  EXPECT_THROW(validateCacheOptions(tile), std::invalid_argument);
  CacheOptions filtered;
  filtered.mode = CacheMode::Texel;
  filtered.filter = CacheFilter::Stochastic;
  filtered.refreshFrames = 4;
  EXPECT_THROW(validateCacheOptions(filtered), std::invalid_argument);
  CacheOptions nearest;
  nearest.mode = CacheMode::Texel;
  nearest.refreshFrames = 4;
  EXPECT_NO_THROW(validateCacheOptions(nearest));
}

// Given, the refresh applies to every key; unset, to voxel keys (object and world space)
// alone, every kDefaultVoxelRefreshFrames frames; never with the tile cache or a filter,
// given or not.
std::vector<std::string> refreshDefines(const CacheOptions& options) {
  std::vector<std::string> refresh;
  for (const std::string& define : cacheShaderDefines(options, 4))
    if (define.rfind("MG_CACHE_REFRESH", 0) == 0)
      refresh.push_back(define);
  return refresh;
}

TEST(CacheRefreshOptions, UnsetItRefreshesVoxelKeysOnlyAndGivenEveryKey) {
  CacheOptions nearest;
  nearest.mode = CacheMode::Texel;
  EXPECT_EQ(kDefaultVoxelRefreshFrames, 16u);
  EXPECT_EQ(refreshDefines(nearest), std::vector<std::string>{"MG_CACHE_REFRESH_VOXEL=16"});
  nearest.refreshFrames = 4;
  EXPECT_EQ(refreshDefines(nearest),
            (std::vector<std::string>{"MG_CACHE_REFRESH_UV=4", "MG_CACHE_REFRESH_VOXEL=4"}));
  nearest.refreshFrames = 0;
  EXPECT_TRUE(refreshDefines(nearest).empty());
  CacheOptions filtered;
  filtered.mode = CacheMode::Texel;
  filtered.filter = CacheFilter::Trilinear;
  EXPECT_NO_THROW(validateCacheOptions(filtered));
  EXPECT_TRUE(refreshDefines(filtered).empty());
  CacheOptions tile;
  tile.mode = CacheMode::Tile;
  EXPECT_NO_THROW(validateCacheOptions(tile));
  EXPECT_TRUE(refreshDefines(tile).empty());
  EXPECT_TRUE(refreshDefines(CacheOptions{}).empty());  // no cache
}

// What bench and render print of it.
TEST(CacheRefreshOptions, ItsTextSaysWhichKeysAreRefreshed) {
  CacheOptions texel;
  texel.mode = CacheMode::Texel;
  EXPECT_EQ(cacheRefreshText(cacheRefreshOf(texel)),
            "keys refreshed: uv never, voxel every 16 frames");
  texel.refreshFrames = 4;
  EXPECT_EQ(cacheRefreshText(cacheRefreshOf(texel)), "keys refreshed every 4 frames");
  texel.refreshFrames = 0;
  EXPECT_EQ(cacheRefreshText(cacheRefreshOf(texel)), "keys refreshed never");
}

}  // namespace
}  // namespace memograph::runtime
