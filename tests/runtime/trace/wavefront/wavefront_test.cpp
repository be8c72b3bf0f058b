// The wavefront path tracer (--shading wavefront) on lavapipe, with the free-material floor
// and with the scenes' material graphs (evaluated in batches sorted by material), with and
// without the texel cache: both backends give the same image, the megakernel's too at the same
// seed (both draw the same counter-based random numbers: the same paths), its mean agrees
// with the megakernel's with either cache, its passes are timed, the cache's lookups spare
// material evaluations, and what the prototype does not do is refused, in the library and the
// CLI.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/renderer.h"
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/scene_upload.h"

namespace memograph::runtime {
namespace {

// `floor` false: the scene's own material graphs (the wavefront's material passes).
RendererOptions floorOptions(Backend backend, Shading shading, bool floor = true) {
  RendererOptions options = testing::testOptions(backend);
  options.nodeLibraryDirectory.clear();  // built-in scenes: the real node library
  options.floorMaterials = floor;
  options.shading = shading;
  return options;
}

RendererOptions graphOptions(Backend backend, Shading shading) {
  return floorOptions(backend, shading, false);
}

// The scene's graphs with a cache (the defaults for the rest: LRU, the counter clock where
// the device has 64-bit atomics; the tile cache's 4x4 tiles, filled by the deferred fill in
// the megakernel, where lavapipe's 8 lanes cannot share 16 texels out).
RendererOptions cachedOptions(Backend backend, Shading shading, CacheMode mode) {
  RendererOptions options = graphOptions(backend, shading);
  options.cache.mode = mode;
  options.cache.entries = mode == CacheMode::Tile ? 1u << 14 : 1u << 16;
  if (mode == CacheMode::Tile)
    options.cache.tileFill = TileFill::Deferred;
  return options;
}

RendererOptions texelCacheOptions(Backend backend, Shading shading) {
  return cachedOptions(backend, shading, CacheMode::Texel);
}

RenderSettings settings(std::uint32_t width, std::uint32_t height, std::uint32_t paths,
                        std::uint32_t bounces, std::uint32_t frames) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.pathsPerPixel = paths;
  s.raysPerPath = bounces;
  s.frames = frames;
  return s;
}

// Mean of the RGB channels over the whole image.
double meanRadiance(const HdrImage& image) {
  double sum = 0.0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    sum += image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2];
  return sum / (3.0 * double(image.width) * image.height);
}

// The wavefront's landscape on the query and the pipeline backend, bitwise the same (the same
// passes, the same numbers; the material passes are compute on both); returns the query's.
RenderResult expectQueryEqualsPipeline(bool floor, std::uint32_t frames) {
  const Scene scene = makeBuiltinScene("landscape", {});
  const RenderSettings s = settings(32, 18, 2, 3, frames);
  RenderResult query =
      Renderer(floorOptions(Backend::RayQuery, Shading::Wavefront, floor)).render(scene, s);
  RenderResult pipeline =
      Renderer(floorOptions(Backend::RayTracingPipeline, Shading::Wavefront, floor))
          .render(scene, s);
  EXPECT_EQ(query.image.rgba.size(), pipeline.image.rgba.size());
  EXPECT_EQ(query.image.rgba, pipeline.image.rgba);
  EXPECT_EQ(query.stats.shading, "wavefront");
  EXPECT_GT(meanRadiance(query.image), 0.0);
  return query;
}

TEST(Wavefront, QueryAndPipelineGiveTheSameImage) {
  expectQueryEqualsPipeline(true, 2);
}

// Relative difference of the wavefront's mean radiance from the megakernel's, both on
// `backend` (with graphs the megakernel's dispatch is the switch on the query backend,
// callables on the pipeline backend), L = 4, at `paths` x `frames` samples per pixel.
double meanDifference(const std::string& sceneName, std::uint32_t width, std::uint32_t height,
                      std::uint32_t paths, std::uint32_t frames,
                      Backend backend = Backend::RayQuery, bool floor = true,
                      CacheMode cache = CacheMode::None) {
  const Scene scene = makeBuiltinScene(sceneName, {});
  const RenderSettings s = settings(width, height, paths, 4, frames);
  auto options = [&](Shading shading) {
    return cache != CacheMode::None ? cachedOptions(backend, shading, cache)
                                    : floorOptions(backend, shading, floor);
  };
  const double megakernel =
      meanRadiance(Renderer(options(Shading::Megakernel)).render(scene, s).image);
  const double wavefront =
      meanRadiance(Renderer(options(Shading::Wavefront)).render(scene, s).image);
  EXPECT_GT(megakernel, 0.0);
  std::printf("%s%s: megakernel mean %.6f, wavefront %.6f (%+.3f %%)\n", sceneName.c_str(),
              cache == CacheMode::Texel  ? " with the texel cache"
              : cache == CacheMode::Tile ? " with the tile cache"
              : floor                    ? ""
                                         : " with graphs",
              megakernel, wavefront, 100.0 * (wavefront / megakernel - 1.0));
  return wavefront / megakernel - 1.0;
}

// Lit by the sun and the sky: 48x27 pixels, 64 samples each. The same paths as the
// megakernel's (AtOneSeedTheMegakernelTracesTheSamePaths): measured 0.000 %; the tolerance is
// the one kept from when the two drew different numbers (-0.05 % then). Without the shadow
// pass (no sun) the wavefront's mean falls far below (measured: -35 %).
TEST(Wavefront, MeanMatchesTheMegakernelOnTheLandscape) {
  EXPECT_LT(std::abs(meanDifference("landscape", 48, 27, 4, 16)), 0.015);
}

// With free materials nothing emits: the classroom's light is its lamps' point lights,
// reached only through shadow rays, often close to a surface (1/d²: fireflies). With
// different random numbers six seeds' means spread by 7 % at these 24x14 pixels and 512
// samples; with the same paths the two agree (measured 0.000 %). Without the shadow pass the
// image is black (measured: -100 %).
TEST(Wavefront, MeanMatchesTheMegakernelOnTheClassroom) {
  EXPECT_LT(std::abs(meanDifference("classroom", 24, 14, 8, 64)), 0.001);
}

// A frame's material bins: how many got hits, and the hits in all of them.
struct BinTally {
  std::uint32_t binsHit = 0;
  std::uint64_t hits = 0;
};

BinTally tallyBins(const FrameStats& frame) {
  BinTally tally;
  for (std::uint32_t count : frame.wavefrontBinHits) {
    tally.binsHit += count > 0 ? 1u : 0u;
    tally.hits += count;
  }
  return tally;
}

// The largest difference between two images of the same size, relative to the larger of
// the two values (at least 1), over every channel of every pixel.
double largestRelativeDifference(const HdrImage& a, const HdrImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
    const double scale = std::max({1.0, std::abs(double(a.rgba[i])), std::abs(double(b.rgba[i]))});
    largest = std::max(largest, std::abs(double(a.rgba[i]) - double(b.rgba[i])) / scale);
  }
  return largest;
}

// At one seed the megakernel and the wavefront trace the same paths (rng.glsl: one generator
// keyed by pixel, sample, bounce and dimension in both), so without a cache their pictures
// agree per pixel, not only in the mean: the floor and the graphs on both backends (the
// megakernel's switch on the query backend, its callables on the pipeline backend, against
// the material passes). What may differ is the compilers' rounding of the same arithmetic in
// other shaders: measured 0 with graphs, 2.4e-7 and 1.1e-6 on the floors, on lavapipe. The
// classroom's floor too (point lights close to surfaces: fireflies, where two generators differed
// by 5 % in the mean).
TEST(Wavefront, AtOneSeedTheMegakernelTracesTheSamePaths) {
  struct Case {
    const char* scene;
    Backend backend;
    bool floor;
  };
  for (const Case& c : {Case{"landscape", Backend::RayQuery, true},
                        Case{"landscape", Backend::RayTracingPipeline, true},
                        Case{"landscape", Backend::RayQuery, false},
                        Case{"landscape", Backend::RayTracingPipeline, false},
                        Case{"classroom", Backend::RayQuery, true}}) {
    const Scene scene = makeBuiltinScene(c.scene, {});
    RenderSettings s = settings(24, 14, 2, 4, 2);
    s.seed = 7;
    const HdrImage megakernel =
        Renderer(floorOptions(c.backend, Shading::Megakernel, c.floor)).render(scene, s).image;
    const HdrImage wavefront =
        Renderer(floorOptions(c.backend, Shading::Wavefront, c.floor)).render(scene, s).image;
    const double difference = largestRelativeDifference(megakernel, wavefront);
    std::printf("%s, %s, %s: largest relative difference %.3g\n", c.scene,
                c.backend == Backend::RayQuery ? "query" : "pipeline", c.floor ? "floor" : "graphs",
                difference);
    EXPECT_LT(difference, 1e-4) << c.scene;
    EXPECT_GT(meanRadiance(megakernel), 0.0) << c.scene;
  }
}

// The classroom's 88 graphs: the megakernel's callables against the wavefront's material
// passes, whose binning reserves one place per distinct bin of a subgroup (addToBinRecord),
// at one seed; its graphs come from 11 recipes, so 11 passes serve the 88 bins (material
// instances), each graph's constants read from its bin's parameters. A hit binned twice or
// lost, or a bin reading another's parameters, would change its pixel; measured within float
// rounding (1.3e-6). About a minute on lavapipe, most of it the megakernel's 88 callables'
// pipeline.
TEST(Wavefront, TheClassroomsGraphsGiveTheMegakernelsPictureAtOneSeed) {
  const Scene scene = makeBuiltinScene("classroom", {});
  RenderSettings s = settings(24, 14, 1, 2, 1);
  s.seed = 7;
  const RenderResult megakernel =
      Renderer(graphOptions(Backend::RayTracingPipeline, Shading::Megakernel)).render(scene, s);
  const RenderResult wavefront =
      Renderer(graphOptions(Backend::RayTracingPipeline, Shading::Wavefront)).render(scene, s);
  EXPECT_EQ(megakernel.stats.shading, "megakernel");
  EXPECT_EQ(wavefront.stats.shading, "wavefront");
  // Counted, not timed: a cold start waits for every one (wavefront_pipeline_count_test.cpp).
  EXPECT_EQ(wavefront.stats.pipelinesCreated, 19u);
  // A driver inlines every call, so each call site of a graph in its pass is a copy of it to
  // compile at a cold start: one a pass, and besides it at most 2,000 instructions of the
  // hit's surface, the outputs' store and the binning's bookkeeping (about 1,600 measured).
  EXPECT_EQ(wavefront.stats.wavefrontMaterialPasses, 11u);
  EXPECT_EQ(wavefront.stats.wavefrontMaterialGraphCopiesMax, 1u);
  EXPECT_LT(wavefront.stats.wavefrontMaterialInlinedInstructions,
            wavefront.stats.wavefrontMaterialGraphInstructions + 11u * 2000u);
  std::printf(
      "classroom material passes: %llu SPIR-V instructions inlined, %llu of them its "
      "graphs'\n",
      static_cast<unsigned long long>(wavefront.stats.wavefrontMaterialInlinedInstructions),
      static_cast<unsigned long long>(wavefront.stats.wavefrontMaterialGraphInstructions));
  const BinTally bins = tallyBins(wavefront.stats.frames.front());
  EXPECT_GE(bins.binsHit, 8u) << "the view should reach many of the classroom's graphs";
  EXPECT_GT(bins.hits, 0u);
  const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
  std::printf(
      "classroom graphs, pipeline: %u bins hit, %llu hits binned, largest relative "
      "difference %.3g\n",
      bins.binsHit, static_cast<unsigned long long>(bins.hits), difference);
  EXPECT_LT(difference, 1e-4);
  EXPECT_GT(meanRadiance(megakernel.image), 0.0);
}

// A round split into chunks (a path state of fewer slots than pixels, --wavefront-paths)
// draws the same random numbers for the same pixels, so the image is the same bit for bit:
// the floor in 3 chunks of 50 of its 144 pixels, the graphs in 21 chunks of 7.
TEST(Wavefront, ARoundSplitIntoChunksGivesTheSameImage) {
  const Scene scene = makeBuiltinScene("landscape", {});
  const RenderSettings s = settings(16, 9, 2, 3, 2);
  for (auto [floor, slots, chunks] : {std::tuple(true, 50u, 3u), std::tuple(false, 7u, 21u)}) {
    RendererOptions whole = floorOptions(Backend::RayQuery, Shading::Wavefront, floor);
    RendererOptions split = whole;
    split.wavefrontPaths = slots;
    RenderResult a = Renderer(whole).render(scene, s);
    RenderResult b = Renderer(split).render(scene, s);
    EXPECT_EQ(a.stats.wavefrontPathSlots, 16u * 9u);
    EXPECT_EQ(a.stats.wavefrontChunks, 1u);
    EXPECT_EQ(b.stats.wavefrontPathSlots, slots);
    EXPECT_EQ(b.stats.wavefrontChunks, chunks);
    EXPECT_EQ(a.image.rgba, b.image.rgba) << (floor ? "floor" : "graphs");
    EXPECT_GT(meanRadiance(b.image), 0.0);
    // The same rays, and the passes of every chunk timed.
    EXPECT_EQ(a.stats.frames.at(1).rays, b.stats.frames.at(1).rays);
    EXPECT_GT(b.stats.frames.at(1).wavefrontTraceMilliseconds, 0.0);
  }
  // The capacity is the wavefront's: the megakernel refuses it.
  RendererOptions megakernel = floorOptions(Backend::RayQuery, Shading::Megakernel);
  megakernel.wavefrontPaths = 64;
  EXPECT_THROW(Renderer(megakernel).render(scene, s), std::invalid_argument);
}

// The statistics of one frame of the landscape.
FrameStats landscapeFrame(const RendererOptions& options, const RenderSettings& s) {
  const Scene scene = makeBuiltinScene("landscape", {});
  RenderResult result = Renderer(options).render(scene, s);
  EXPECT_EQ(result.stats.frames.size(), 1u);
  return result.stats.frames.at(0);
}

TEST(Wavefront, PassesAreTimedAndRaysCounted) {
  const FrameStats frame =
      landscapeFrame(floorOptions(Backend::RayQuery, Shading::Wavefront), settings(16, 9, 2, 3, 1));
  EXPECT_GT(frame.wavefrontTraceMilliseconds, 0.0);
  EXPECT_GT(frame.wavefrontShadeMilliseconds, 0.0);
  EXPECT_GT(frame.wavefrontShadowMilliseconds, 0.0);
  EXPECT_GT(frame.wavefrontQueueMilliseconds, 0.0);
  EXPECT_GE(frame.gpuMilliseconds, frame.wavefrontTraceMilliseconds +
                                       frame.wavefrontShadeMilliseconds +
                                       frame.wavefrontShadowMilliseconds);
  // At least every camera ray (2 paths a pixel), at most L path rays and L shadow rays each.
  EXPECT_GE(frame.rays, 16u * 9u * 2u);
  EXPECT_LE(frame.rays, 16u * 9u * 2u * 3u * 2u);
}

TEST(Wavefront, OptionsThePrototypeLacksAreRefused) {
  const Scene scene = makeBuiltinScene("landscape", {});
  const RenderSettings s = settings(8, 8, 1, 2, 1);
  auto refuses = [&](RendererOptions options, const RenderSettings& settings,
                     const std::string& named) {
    try {
      Renderer(options).render(scene, settings);
      ADD_FAILURE() << "rendered; expected a refusal naming " << named;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  };
  // The caches need the material passes (the floor has none).
  RendererOptions cached = floorOptions(Backend::RayQuery, Shading::Wavefront);
  cached.cache.mode = CacheMode::Texel;
  refuses(cached, s, "floor");
  RendererOptions tiled = floorOptions(Backend::RayQuery, Shading::Wavefront);
  tiled.cache.mode = CacheMode::Tile;
  refuses(tiled, s, "floor");
  // The wavefront computes tiles from the deferred fill's queue: an explicit subgroup fill is
  // refused, not replaced (refused before the device's subgroup size is checked).
  RendererOptions subgroupFill = graphOptions(Backend::RayQuery, Shading::Wavefront);
  subgroupFill.cache.mode = CacheMode::Tile;
  subgroupFill.cache.tileFill = TileFill::Subgroup;
  refuses(subgroupFill, s, "--tile-fill subgroup");
  EXPECT_THROW(parseShading("wave"), std::invalid_argument);
  EXPECT_EQ(parseShading("wavefront"), Shading::Wavefront);
}

TEST(Wavefront, ParseShadingTakesAutoAndNamesAllThree) {
  EXPECT_EQ(parseShading("auto"), Shading::Auto);
  EXPECT_EQ(parseShading("megakernel"), Shading::Megakernel);
  EXPECT_EQ(std::string(shadingName(Shading::Auto)), "auto");
  EXPECT_EQ(RendererOptions{}.shading, Shading::Auto);
  try {
    parseShading("sideways");
    ADD_FAILURE() << "parsed 'sideways'";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    for (const char* name : {"auto", "megakernel", "wavefront", "sideways"})
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

// Auto: the wavefront on a GPU when it does all that is asked (it was faster in every
// configuration measured on an H200), else the megakernel, never a refusal. Culling, the
// debug views and animated meshes (the frame loop's, for either architecture) are the
// wavefront's on a GPU.
TEST(Wavefront, AutoShadingPicksTheWavefrontOnlyOnAGpuAndOnlyForWhatItDoes) {
  const Scene scene = makeBuiltinScene("landscape", {});
  const ShadingDevice gpu{VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, true};
  const ShadingDevice cpu{VK_PHYSICAL_DEVICE_TYPE_CPU, true};
  auto pick = [&](const RendererOptions& options,
                  const ShadingDevice& device = {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, true}) {
    const ShadingChoice choice = resolveShading(options, device);
    EXPECT_NE(choice.shading, Shading::Auto);
    EXPECT_EQ(choice.whyMegakernel.empty(),
              options.shading != Shading::Auto || choice.shading == Shading::Wavefront);
    return choice.shading;
  };
  const RendererOptions plain;
  EXPECT_EQ(pick(plain, gpu), Shading::Wavefront);
  EXPECT_EQ(pick(plain, {VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, true}), Shading::Wavefront);
  EXPECT_EQ(pick(plain, cpu), Shading::Megakernel);
  // The pipeline backend without indirect trace launches.
  EXPECT_EQ(pick(plain, {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, false}), Shading::Megakernel);
  // Both caches with the scene's graphs, and the floor without a cache, are the wavefront's.
  for (CacheMode mode : {CacheMode::Texel, CacheMode::Tile}) {
    RendererOptions cached;
    cached.cache.mode = mode;
    EXPECT_EQ(pick(cached), Shading::Wavefront) << cacheModeName(mode);
    cached.floorMaterials = true;
    EXPECT_EQ(pick(cached), Shading::Megakernel) << cacheModeName(mode);
  }
  RendererOptions floor;
  floor.floorMaterials = true;
  EXPECT_EQ(pick(floor), Shading::Wavefront);
  RendererOptions culled;
  for (CullingMode mode : {CullingMode::Frustum, CullingMode::Lipac}) {
    culled.culling.mode = mode;
    EXPECT_EQ(pick(culled), Shading::Wavefront) << cullingModeName(mode);
    EXPECT_EQ(pick(culled, {VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, true}), Shading::Wavefront);
    EXPECT_EQ(pick(culled, cpu), Shading::Megakernel) << cullingModeName(mode);
    RendererOptions cullingView = culled;
    cullingView.debugCullingSize = 64;
    EXPECT_EQ(pick(cullingView), Shading::Wavefront) << cullingModeName(mode);
    EXPECT_EQ(pick(cullingView, cpu), Shading::Megakernel) << cullingModeName(mode);
  }
  RendererOptions misses;
  misses.debugCacheMisses = true;
  for (CacheMode mode : {CacheMode::Texel, CacheMode::Tile}) {
    misses.cache.mode = mode;
    EXPECT_EQ(pick(misses), Shading::Wavefront) << cacheModeName(mode);
    EXPECT_EQ(pick(misses, cpu), Shading::Megakernel) << cacheModeName(mode);
  }
  // Whether NEE must evaluate an emitter's graph (the wavefront's material passes after the
  // shadow pass do): the landscape has no emitter; one whose emission is its graph's counts,
  // unless NEE does not sample emitters.
  EXPECT_FALSE(sceneNeeEvaluatesEmission(scene, {}));
  Scene emitting = scene;
  emitting.materials[0].emissionEstimate = glm::vec3(1.0f);
  emitting.materials[0].emissionKind = MaterialRef::EmissionKind::Graph;
  EXPECT_TRUE(sceneNeeEvaluatesEmission(emitting, {}));
  emitting.emissiveLightSampling = false;
  EXPECT_FALSE(sceneNeeEvaluatesEmission(emitting, {}));
  // An explicit --tile-fill subgroup (unset, the wavefront queues; deferred is fine), and the
  // subgroup fill's grouping and test hook.
  RendererOptions tiled;
  tiled.cache.mode = CacheMode::Tile;
  tiled.cache.tileFill = TileFill::Deferred;
  EXPECT_EQ(pick(tiled), Shading::Wavefront);
  tiled.cache.tileFill = TileFill::Subgroup;
  EXPECT_EQ(pick(tiled), Shading::Megakernel);
  RendererOptions grouped;
  grouped.cache.mode = CacheMode::Tile;
  grouped.cache.groupByMaterial = true;
  EXPECT_EQ(pick(grouped), Shading::Megakernel);
  // An explicit choice stands, on any device and with any option.
  RendererOptions megakernel;
  megakernel.shading = Shading::Megakernel;
  EXPECT_EQ(pick(megakernel, gpu), Shading::Megakernel);
  RendererOptions wavefront = plain;
  wavefront.shading = Shading::Wavefront;
  EXPECT_EQ(pick(wavefront, cpu), Shading::Wavefront);
}

// On lavapipe (a CPU) auto runs the megakernel, and the stats say so; --wavefront-paths
// needs the wavefront, which auto did not choose.
TEST(Wavefront, AutoRunsTheMegakernelOnLavapipe) {
  const Scene scene = makeBuiltinScene("landscape", {});
  RendererOptions options = floorOptions(Backend::RayQuery, Shading::Auto);
  ASSERT_EQ(RendererOptions{}.shading, testing::testOptions(Backend::RayQuery).shading);
  EXPECT_EQ(Renderer(options).render(scene, settings(8, 8, 1, 2, 1)).stats.shading, "megakernel");
  options.wavefrontPaths = 64;
  try {
    Renderer(options).render(scene, settings(8, 8, 1, 2, 1));
    ADD_FAILURE() << "rendered; expected --wavefront-paths refused";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("--wavefront-paths"), std::string::npos) << message;
    EXPECT_NE(message.find("CPU"), std::string::npos) << message;
  }
}

// With the scenes' graphs: the same passes, plus the binning passes and one material
// pipeline per distinct graph; the same numbers on both backends (the material passes are
// compute on both, and the traces find the same hits).
TEST(Wavefront, GraphsGiveTheSameImageOnQueryAndPipeline) {
  EXPECT_EQ(expectQueryEqualsPipeline(false, 1).stats.materialDispatch, "batched");
}

// The floor's landscape tolerance (1.5 %) at the same 48x27 pixels and 64 samples; measured
// 0.000 % on both backends (the same paths; -0.038 % with different random numbers).
TEST(Wavefront, GraphMeanMatchesTheMegakernelOnTheLandscapeWithQuery) {
  EXPECT_LT(std::abs(meanDifference("landscape", 48, 27, 4, 16, Backend::RayQuery, false)), 0.015);
}

TEST(Wavefront, GraphMeanMatchesTheMegakernelOnTheLandscapeWithPipeline) {
  EXPECT_LT(
      std::abs(meanDifference("landscape", 48, 27, 4, 16, Backend::RayTracingPipeline, false)),
      0.015);
}

// Every distinct graph the camera sees gets a batch: the landscape's hits land in more than
// one bin, and the bins together hold at most one hit a path ray (32x18 pixels, P = 1, L = 2).
TEST(Wavefront, HitsAreBinnedByMaterial) {
  const FrameStats frame = landscapeFrame(graphOptions(Backend::RayQuery, Shading::Wavefront),
                                          settings(32, 18, 1, 2, 1));
  const BinTally bins = tallyBins(frame);
  for (std::uint32_t count : frame.wavefrontBinHits)
    EXPECT_LE(count, 32u * 18u * 2u);
  EXPECT_GE(frame.wavefrontBinHits.size(), 2u);
  EXPECT_GE(bins.binsHit, 2u);
  EXPECT_GT(bins.hits, 0u);
  EXPECT_LE(bins.hits, 32u * 18u * 2u);
  EXPECT_GT(frame.wavefrontMaterialMilliseconds, 0.0);
  EXPECT_GT(frame.wavefrontBinMilliseconds, 0.0);
}

// With the texel cache (thesis §5.3) the lookup pass reads every live hit first and only the
// misses reach the material passes, which insert them: the mean stays the megakernel's with
// the same cache (the landscape at the graphs' 48x27 pixels and 64 samples, tolerance 1.5 %).
TEST(Wavefront, TexelCacheMeanMatchesTheMegakernelsWithTheCache) {
  EXPECT_LT(std::abs(meanDifference("landscape", 48, 27, 4, 16, Backend::RayQuery, false,
                                    CacheMode::Texel)),
            0.015);
}

// LRU with the counter clock (§5.3.3) ticks the clock once for every hit and every write. The
// wavefront's lookup pass stamps a subgroup's hits with one atomic (cacheStampReads): each
// frame's ticks must still lie between its hits and its hits plus misses (a write for at
// most every miss), in both architectures. Without the deferred stamps the wavefront's ticks
// fall to its writes alone, below its hits.
TEST(Wavefront, TheCounterClockTicksForEveryHitAndWriteInBothArchitectures) {
  const Scene scene = makeBuiltinScene("landscape", {});
  const RenderSettings s = settings(32, 18, 2, 3, 4);
  for (Shading shading : {Shading::Megakernel, Shading::Wavefront}) {
    RendererOptions options = texelCacheOptions(Backend::RayQuery, shading);
    options.cache.eviction = CacheEviction::Lru;
    options.cache.clock = CacheClock::Counter;
    options.cache.clockShift = 0;
    const RenderResult r = Renderer(options).render(scene, s);
    EXPECT_EQ(r.stats.cacheClock, "counter");
    for (std::size_t f = 1; f < r.stats.frames.size(); ++f) {
      const FrameStats& frame = r.stats.frames[f];
      const std::uint64_t ticks = frame.cacheClockTicks - r.stats.frames[f - 1].cacheClockTicks;
      std::printf("%s frame %zu: %llu ticks, %llu hits, %llu misses\n", shadingName(shading), f,
                  (unsigned long long)ticks, (unsigned long long)frame.cacheHits,
                  (unsigned long long)frame.cacheMisses);
      EXPECT_GT(frame.cacheHits, 0u);
      EXPECT_GE(ticks, frame.cacheHits) << shadingName(shading) << " frame " << f;
      EXPECT_LE(ticks, frame.cacheHits + frame.cacheMisses)
          << shadingName(shading) << " frame " << f;
    }
  }
}

// The tile cache (§5.4) in the wavefront: the lookup pass reads the hit's tile and queues a
// missing one; each bin's material pass computes its queued tiles after its hits, so the
// next bounce finds them (the megakernel's deferred fill computes them after the frame).
// The same tiles, so the same mean within the graphs' 1.5 %.
TEST(Wavefront, TileCacheMeanMatchesTheMegakernelsWithTheCache) {
  EXPECT_LT(std::abs(meanDifference("landscape", 48, 27, 4, 16, Backend::RayQuery, false,
                                    CacheMode::Tile)),
            0.015);
}

// The tile cache's counts add up, tiles are computed and then hit, and a tile queue far too
// small for a frame's misses gives up the rest, counted, the picture still finite.
TEST(Wavefront, TileCacheComputesQueuedTilesAndCountsAFullQueue) {
  const Scene scene = makeBuiltinScene("landscape", {});
  RenderResult result =
      Renderer(cachedOptions(Backend::RayQuery, Shading::Wavefront, CacheMode::Tile))
          .render(scene, settings(32, 18, 2, 3, 2));
  ASSERT_EQ(result.stats.frames.size(), 2u);
  const FrameStats& first = result.stats.frames[0];
  const FrameStats& second = result.stats.frames[1];
  for (const FrameStats* frame : {&first, &second}) {
    EXPECT_GT(frame->cacheLookups, 0u);
    EXPECT_EQ(frame->cacheLookups, frame->cacheHits + frame->cacheMisses);
    EXPECT_LE(frame->cacheTilesComputed, frame->cacheMisses);
  }
  EXPECT_GT(first.cacheTilesComputed, 0u);
  EXPECT_EQ(first.cacheTileFallbacks, 0u);
  EXPECT_GT(second.cacheHitRate(), first.cacheHitRate());
  std::printf("tile cache: hit rate %.3f then %.3f, %llu then %llu tiles computed\n",
              first.cacheHitRate(), second.cacheHitRate(),
              (unsigned long long)first.cacheTilesComputed,
              (unsigned long long)second.cacheTilesComputed);

  RendererOptions tiny = cachedOptions(Backend::RayQuery, Shading::Wavefront, CacheMode::Tile);
  tiny.cache.tileQueue = 2;
  RenderResult full = Renderer(tiny).render(scene, settings(32, 18, 2, 3, 1));
  const FrameStats& frame = full.stats.frames.at(0);
  EXPECT_GT(frame.cacheTileFallbacks, 0u);
  EXPECT_LE(frame.cacheTilesComputed, 2u * 2u * 3u);  // 2 a bounce, 3 bounces, 2 rounds
  for (float value : full.image.rgba)
    ASSERT_TRUE(std::isfinite(value));
  std::printf("tile queue of 2: %llu tiles computed, %llu given up\n",
              (unsigned long long)frame.cacheTilesComputed,
              (unsigned long long)frame.cacheTileFallbacks);
}

// The cache's counts add up, its lookup pass is timed, and a warm cache spares evaluations:
// the second frame's material passes evaluate fewer hits than the first's, and at least its
// misses (each miss is evaluated; hits of materials the cache does not take are too).
TEST(Wavefront, TexelCacheLookupsSpareMaterialEvaluations) {
  const Scene scene = makeBuiltinScene("landscape", {});
  RenderResult result = Renderer(texelCacheOptions(Backend::RayQuery, Shading::Wavefront))
                            .render(scene, settings(32, 18, 2, 3, 2));
  ASSERT_EQ(result.stats.frames.size(), 2u);
  auto evaluated = [](const FrameStats& frame) {
    std::uint64_t sum = 0;
    for (std::uint32_t count : frame.wavefrontBinHits)
      sum += count;
    return sum;
  };
  const FrameStats& first = result.stats.frames[0];
  const FrameStats& second = result.stats.frames[1];
  for (const FrameStats* frame : {&first, &second}) {
    EXPECT_GT(frame->cacheLookups, 0u);
    EXPECT_EQ(frame->cacheLookups, frame->cacheHits + frame->cacheMisses);
    EXPECT_GE(evaluated(*frame), frame->cacheMisses);
    EXPECT_GT(frame->wavefrontLookupMilliseconds, 0.0);
  }
  EXPECT_GT(second.cacheHits, first.cacheHits);
  EXPECT_LT(evaluated(second), evaluated(first));
  std::printf("evaluated %llu then %llu; hit rate %.3f then %.3f\n",
              (unsigned long long)evaluated(first), (unsigned long long)evaluated(second),
              first.cacheHitRate(), second.cacheHitRate());
}

// The classroom's 88 graphs do not compile into the query backend's megakernel on lavapipe;
// the wavefront compiles each into a pipeline of its own, so the query backend renders it,
// here with the texel cache looked up and filled by those pipelines.
TEST(Wavefront, TheClassroomRendersWithGraphsOnTheQueryBackend) {
  const Scene scene = makeBuiltinScene("classroom", {});
  RenderResult result = Renderer(texelCacheOptions(Backend::RayQuery, Shading::Wavefront))
                            .render(scene, settings(32, 18, 1, 2, 1));
  EXPECT_GT(result.stats.frames.at(0).cacheLookups, 0u);
  double sum = 0.0;
  for (float value : result.image.rgba) {
    ASSERT_TRUE(std::isfinite(value));
    sum += value;
  }
  EXPECT_GT(sum, 0.0);
  EXPECT_GE(tallyBins(result.stats.frames.at(0)).binsHit, 2u);
}

#ifdef MEMOGRAPH_CLI
// Exit status of the memograph CLI with `arguments`, output discarded.
int runCli(const std::string& arguments) {
  const int status =
      std::system((std::string(MEMOGRAPH_CLI) + " " + arguments + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Wavefront, TheCliRefusesBadCombinationsAsUsageErrors) {
  const std::string out =
      (std::filesystem::temp_directory_path() / "memograph_wavefront_refused.pfm").string();
  const std::string render = "render builtin:landscape --size 8x8 --out " + out + " ";
  EXPECT_EQ(runCli(render + "--shading wavefront --floor-materials --cache texel"), 2);
  // --debug-misses needs a cache, which the floor has none of in the wavefront.
  EXPECT_EQ(runCli(render + "--shading wavefront --floor-materials --debug-misses"), 2);
  EXPECT_EQ(runCli(render + "--shading sideways --floor-materials"), 2);
  EXPECT_EQ(runCli(render + "--floor-materials --wavefront-paths 64"), 2);  // auto: megakernel
  EXPECT_EQ(runCli(render + "--shading megakernel --floor-materials --wavefront-paths 64"), 2);
  EXPECT_EQ(runCli(render + "--shading wavefront --cache tile --tile-fill subgroup"), 2);
  EXPECT_EQ(runCli(render + "--shading wavefront --floor-materials --wavefront-paths many"), 2);
  EXPECT_FALSE(std::filesystem::exists(out));
  // Without --floor-materials it renders the scene's graphs.
  EXPECT_EQ(runCli(render + "--shading wavefront --paths 1 --bounces 2"), 0);
  EXPECT_TRUE(std::filesystem::exists(out));
  std::filesystem::remove(out);
  // Auto (the default, spelled out) renders the animated city: the megakernel on lavapipe;
  // the wavefront renders it too (its flags are animated), culled by LiPaC.
  for (const char* shading : {"auto", "wavefront"}) {
    EXPECT_EQ(runCli("render builtin:city:scale=0.02 --size 8x8 --out " + out + " --shading " +
                     shading + " --floor-materials --culling lipac"),
              0)
        << shading;
    EXPECT_TRUE(std::filesystem::exists(out)) << shading;
    std::filesystem::remove(out);
  }
}

TEST(Wavefront, BenchCsvHasThePassColumns) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string wavefront = (dir / "memograph_wavefront_bench.csv").string();
  const std::string megakernel = (dir / "memograph_megakernel_bench.csv").string();
  const std::string bench =
      "bench builtin:landscape --sizes 16x9 --paths 1 --bounces 2 --frames 2 --warmup 0 "
      "--floor-materials --backend query ";
  ASSERT_EQ(runCli(bench + "--shading wavefront --csv " + wavefront), 0);
  ASSERT_EQ(runCli(bench + "--csv " + megakernel), 0);
  auto lines = [](const std::string& path) {
    std::ifstream in(path);
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    return std::pair(header, row);
  };
  auto [header, row] = lines(wavefront);
  EXPECT_NE(header.find(",shading,median_wavefront_trace_gpu_ms,median_wavefront_shade_gpu_ms,"
                        "median_wavefront_shadow_gpu_ms,median_wavefront_queue_gpu_ms,"
                        "median_wavefront_bin_gpu_ms,median_wavefront_material_gpu_ms,"
                        "median_wavefront_lookup_gpu_ms,median_wavefront_traced_inputs_gpu_ms,"
                        "wavefront_paths,wavefront_chunks,"
                        "frames_requested,stopped_early"),
            std::string::npos)
      << header;
  EXPECT_NE(row.find(",wavefront,"), std::string::npos) << row;
  EXPECT_TRUE(row.ends_with(",144,1,2,0")) << row;                // 16x9 paths in flight, one chunk
  EXPECT_EQ(row.find(",wavefront,,"), std::string::npos) << row;  // the medians are there
  // frames_requested, stopped_early stay last (checked above with the wavefront's two)
  auto [megakernelHeader, megakernelRow] = lines(megakernel);
  EXPECT_EQ(megakernelHeader, header);
  EXPECT_NE(megakernelRow.find(",megakernel,,,,,,,,,,,2,0"), std::string::npos) << megakernelRow;
  std::filesystem::remove(wavefront);
  std::filesystem::remove(megakernel);
}
#endif

}  // namespace
}  // namespace memograph::runtime
