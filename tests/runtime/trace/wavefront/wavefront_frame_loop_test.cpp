// What the frame loop does around the trace, with the wavefront tracing (--shading
// wavefront) against the megakernel on lavapipe, at one seed: frustum culling and LiPaC (its
// looks, counting frames, sampled blocks and paths, the shared primary ray) keep the same
// instances and count the same hits, the animated city moves the same way, and both debug
// views show the same. The two architectures draw the same random numbers (rng.glsl), so
// they trace the same paths; what may differ is the compilers' rounding (1e-4 of a pixel's
// value, as Wavefront.AtOneSeedTheMegakernelTracesTheSamePaths states).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/renderer.h"
#include "runtime/scene/builtin/builtin_scenes.h"

namespace memograph::runtime {
namespace {

Scene smallCity() {
  BuiltinSceneOptions options;
  options.cityScale = 0.02;
  return makeBuiltinScene("city", options);
}

RendererOptions options(Shading shading, CullingMode culling) {
  RendererOptions o = testing::testOptions(Backend::RayQuery);
  o.nodeLibraryDirectory.clear();  // built-in scenes: the real node library
  o.floorMaterials = true;         // the culling does not depend on the materials
  o.shading = shading;
  o.culling.mode = culling;
  return o;
}

// 32x18, P = 2, L = 2 (a camera ray and one bounce), a static camera over `frames` frames.
RenderSettings settings(std::uint32_t frames) {
  RenderSettings s;
  s.width = 32;
  s.height = 18;
  s.pathsPerPixel = 2;
  s.raysPerPath = 2;
  s.frames = frames;
  s.seed = 7;
  return s;
}

RenderResult render(const RendererOptions& o, const Scene& scene, const RenderSettings& s) {
  Renderer renderer(o);
  RenderResult result = renderer.render(scene, s);
  EXPECT_TRUE(renderer.context().validationErrors().empty())
      << renderer.context().validationErrors().front();
  EXPECT_EQ(result.stats.shading, shadingName(o.shading));
  return result;
}

// The largest difference of a channel, relative to the larger of the two values or 1.
double largestRelativeDifference(const HdrImage& a, const HdrImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
    const double scale = std::max({1.0, std::abs(double(a.rgba[i])), std::abs(double(b.rgba[i]))});
    largest = std::max(largest, std::abs(double(a.rgba[i]) - double(b.rgba[i])) / scale);
  }
  return largest;
}

double meanRadiance(const HdrImage& image) {
  double sum = 0.0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    sum += image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2];
  return sum / (3.0 * double(image.width) * image.height);
}

// Renders `scene` with both architectures and expects the same picture (1e-4 of a pixel's
// value) and, frame by frame, the same culling: instance states and their changes, looks,
// LiPaC's counts (made and arrived) and the rays (with the shared primary ray one camera ray a
// pixel in both).
void expectSameFrames(const Scene& scene, RendererOptions o, const RenderSettings& s,
                      const std::string& what) {
  SCOPED_TRACE(what);
  o.shading = Shading::Megakernel;
  const RenderResult megakernel = render(o, scene, s);
  o.shading = Shading::Wavefront;
  const RenderResult wavefront = render(o, scene, s);
  EXPECT_EQ(wavefront.instanceStates, megakernel.instanceStates);
  ASSERT_EQ(wavefront.stats.frames.size(), megakernel.stats.frames.size());
  std::uint64_t counted = 0;
  std::uint32_t looks = 0;
  for (std::size_t f = 0; f < megakernel.stats.frames.size(); ++f) {
    const FrameStats& m = megakernel.stats.frames[f];
    const FrameStats& w = wavefront.stats.frames[f];
    EXPECT_EQ(w.looks, m.looks) << "frame " << f;
    EXPECT_EQ(w.lookRays, m.lookRays) << "frame " << f;
    EXPECT_EQ(w.feedbackFrame, m.feedbackFrame) << "frame " << f;
    EXPECT_EQ(w.feedbackCounts, m.feedbackCounts) << "frame " << f;
    EXPECT_EQ(w.feedbackCountsArrived, m.feedbackCountsArrived) << "frame " << f;
    EXPECT_EQ(w.feedbackCountsArrived, w.feedbackCounts) << "frame " << f;
    EXPECT_EQ(w.instanceStateChanges, m.instanceStateChanges) << "frame " << f;
    EXPECT_EQ(w.rays, m.rays) << "frame " << f;
    counted += w.feedbackCountsArrived;
    looks += w.looks;
  }
  if (o.culling.mode == CullingMode::Lipac) {
    EXPECT_GT(counted, 0u) << "LiPaC counted nothing";
    EXPECT_GT(looks, 0u) << "LiPaC looked at no frame";
  }
  const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
  std::printf("%s: largest relative difference %.3g, %llu counts\n", what.c_str(), difference,
              static_cast<unsigned long long>(counted));
  EXPECT_LT(difference, 1e-4);
  EXPECT_GT(meanRadiance(megakernel.image), 0.0);
}

// Frustum culling and LiPaC on the small city (whose flags are animated): every frame
// counting every ray; one frame in two counting, 1 block in 2 and 1 path in 2 (each counted
// ray weighted 4); the shared primary ray, which the megakernel traces once a pixel and
// counts once; and the sampled counts on the pipeline backend. Fails where the wavefront counts a
// ray the megakernel does not, or with another weight (the states or the counts differ), or refuses
// culling.
TEST(WavefrontFrameLoop, CullingKeepsAndCountsWhatTheMegakernelDoes) {
  const Scene scene = smallCity();
  ASSERT_FALSE(scene.animatedMeshes.empty());
  expectSameFrames(scene, options(Shading::Wavefront, CullingMode::Frustum), settings(3),
                   "frustum");
  RendererOptions every = options(Shading::Wavefront, CullingMode::Lipac);
  every.culling.feedbackEvery = 1;
  every.culling.feedbackStride = 1;
  every.culling.feedbackPaths = 0;
  expectSameFrames(scene, every, settings(4), "lipac, every ray counted");
  RendererOptions sampled = every;
  sampled.culling.feedbackEvery = 2;
  sampled.culling.feedbackStride = 2;
  sampled.culling.feedbackPaths = 1;
  expectSameFrames(scene, sampled, settings(4), "lipac, sampled");
  RenderSettings shared = settings(4);
  shared.sharedPrimaryRay = true;
  expectSameFrames(scene, every, shared, "lipac, shared primary ray");
  // The pipeline backend: the trace pass a raygen, its probe a traceRayEXT into the boxes.
  RendererOptions pipeline = sampled;
  pipeline.context.backend = Backend::RayTracingPipeline;
  expectSameFrames(scene, pipeline, settings(4), "lipac, sampled, pipeline backend");
}

// The animated city without culling: its meshes move each frame (the vertex pass and the
// BLAS updates before the trace), the same in both; a camera path of one camera, so the
// frames add up.
TEST(WavefrontFrameLoop, AnimatedMeshesMoveAsInTheMegakernel) {
  const Scene scene = smallCity();
  ASSERT_FALSE(scene.animatedMeshes.empty());
  ASSERT_FALSE(scene.animatedMotions.empty());
  RenderSettings s = settings(3);
  s.secondsPerFrame = 0.5f;
  expectSameFrames(scene, options(Shading::Wavefront, CullingMode::None), s, "animated");
}

// --shared-primary (thesis §5.1): the wavefront traces a pixel's camera ray in round 0 and
// the later rounds take its hit, so it traces the megakernel's rays (one camera ray a pixel,
// not P) and gives its picture; a round split into chunks (50 slots for 576 pixels) keeps each
// chunk's hits apart, the same image bit for bit. Fails where the later rounds trace again
// (rays) or take another pixel's hit (the picture).
TEST(WavefrontFrameLoop, TheSharedPrimaryRayIsTracedOnceAPixel) {
  const Scene scene = smallCity();
  RenderSettings s = settings(2);
  s.pathsPerPixel = 4;
  s.sharedPrimaryRay = true;
  expectSameFrames(scene, options(Shading::Wavefront, CullingMode::None), s, "shared primary");
  RendererOptions split = options(Shading::Wavefront, CullingMode::None);
  split.wavefrontPaths = 50;
  const RenderResult chunked = render(split, scene, s);
  const RenderResult whole = render(options(Shading::Wavefront, CullingMode::None), scene, s);
  EXPECT_EQ(chunked.stats.wavefrontChunks, 12u);
  EXPECT_EQ(chunked.image.rgba, whole.image.rgba);
  EXPECT_EQ(chunked.stats.frames.back().rays, whole.stats.frames.back().rays);
}

// --debug-culling: the top view of what culling kept, drawn from the last frame's states.
TEST(WavefrontFrameLoop, TheCullingViewIsTheMegakernels) {
  const Scene scene = smallCity();
  RendererOptions o = options(Shading::Megakernel, CullingMode::Lipac);
  o.debugCullingSize = 48;
  const RenderResult megakernel = render(o, scene, settings(2));
  o.shading = Shading::Wavefront;
  const RenderResult wavefront = render(o, scene, settings(2));
  ASSERT_EQ(megakernel.cullingView.width, 48u);
  EXPECT_EQ(wavefront.cullingView.width, megakernel.cullingView.width);
  EXPECT_EQ(wavefront.cullingView.rgba, megakernel.cullingView.rgba);
  EXPECT_GT(meanRadiance(wavefront.cullingView), 0.0);
}

// The share of pure red pixels (1, 0, 0): the debug view's cache misses.
double redShare(const HdrImage& image) {
  std::size_t red = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    red += image.rgba[i] == 1.0f && image.rgba[i + 1] == 0.0f && image.rgba[i + 2] == 0.0f;
  return double(red) / (double(image.width) * image.height);
}

// --debug-misses (thesis Fig. 6.9): red where a path of the pixel missed the cache in the
// frame, the frame's own picture elsewhere. Both caches on the landscape's graphs. The first
// frame starts with an empty cache, so nearly every pixel whose paths reach a cached material
// misses; by the third a static camera's texels are mostly cached. Within a frame the two
// architectures fill the cache in another order (the megakernel's threads find what others
// of the same frame inserted; the wavefront's lookups of a bounce all precede its inserts),
// so the pixels that miss may differ: the shares of red pixels agree within 0.1 of the image
// (measured 0.05 and 0.01 in the first frame, 0.002 and 0.001 in the third, on lavapipe).
TEST(WavefrontFrameLoop, TheCacheMissViewShowsTheMegakernelsMisses) {
  const Scene scene = makeBuiltinScene("landscape", {});
  for (CacheMode mode : {CacheMode::Texel, CacheMode::Tile}) {
    SCOPED_TRACE(std::string(cacheModeName(mode)));
    RendererOptions o = options(Shading::Megakernel, CullingMode::None);
    o.floorMaterials = false;
    o.cache.mode = mode;
    o.cache.entries = mode == CacheMode::Tile ? 1u << 14 : 1u << 16;
    if (mode == CacheMode::Tile)
      o.cache.tileFill = TileFill::Deferred;
    o.debugCacheMisses = true;
    // Frames 0 and 2 of one render of 3 (each view is its frame's alone).
    RenderSettings s = settings(3);
    auto missViews = [&](Shading shading) {
      std::vector<HdrImage> views;
      s.frameImageWanted = [](std::uint32_t f) { return f != 1; };
      s.onFrameImage = [&](std::uint32_t, const HdrImage& image) { views.push_back(image); };
      RendererOptions r = o;
      r.shading = shading;
      render(r, scene, s);
      return views;
    };
    const std::vector<HdrImage> megakernel = missViews(Shading::Megakernel);
    const std::vector<HdrImage> wavefront = missViews(Shading::Wavefront);
    ASSERT_EQ(megakernel.size(), 2u);
    ASSERT_EQ(wavefront.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      const double m = redShare(megakernel[i]), f = redShare(wavefront[i]);
      std::printf("%s, frame %zu: red share megakernel %.3f, wavefront %.3f\n",
                  std::string(cacheModeName(mode)).c_str(), 2 * i, m, f);
      EXPECT_NEAR(f, m, 0.1) << "frame " << 2 * i;
    }
    EXPECT_GT(redShare(wavefront[0]), 0.3) << "an empty cache: most pixels miss";
    EXPECT_LT(redShare(wavefront[1]), redShare(wavefront[0])) << "a warm cache misses less";
  }
}

}  // namespace
}  // namespace memograph::runtime
