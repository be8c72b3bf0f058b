// The texel cache with a material of BSDF lobes (nodes/bsdf.inc): a uv-only Mix Shader of a
// Diffuse and a Glossy lobe, its factor a checker, is cached whole, so its lobes go through
// cachePack / cacheUnpack (kCacheOutputLobes) and, in the wavefront, the path state's lobe
// fields. The cached image must differ from the uncached one no more than the same checker
// through the Principled outputs does (the cache's texel quantisation of the checker's
// edges), and keep the sphere's colour. The same for a Principled BSDF with its sheen,
// clearcoat and transmission layers (PrincipledLayers: four lobes over the Principled
// outputs), the checker driving its base colour, sheen, clearcoat and transmission, in the
// wavefront (its entries go through cachePack / cacheUnpack and the path state's lobe
// fields). And a Mix Shader of two layered Principled BSDFs chosen per hit (ChooseShader,
// PrincipledBsdf: eight lobes, four at a hit), in the wavefront, whose lookup pass finishes
// cut entries itself: the checker is the cut, the choice runs per hit after it, never cached,
// so the cached image keeps the uncached one's colours. And a Diffuse lobe about a normal of
// its own, whose normal the entries carry (kCacheOutputLobeNormals).
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "texel_cache_scenes.h"

namespace memograph::runtime {
namespace {

using testing::cacheOptions;
using testing::meanFlip;

const char* const kLobesGraph =
    "material Lobes;\n"
    "UVInput Out>0;\n"
    "CheckerTexture Vector<0 Scale=4 Fac>1;\n"
    "MixShader Fac<1 WeightA>2 WeightB>3;\n"
    "DiffuseBsdf Color=(0.9, 0.2, 0.1) Weight<2;\n"
    "GlossyBsdf Color=(0.2, 0.9, 0.3) Roughness=0.3 Weight<3;\n";

const char* const kPrincipledLayersGraph =
    "material Lobes;\n"
    "UVInput Out>0;\n"
    "CheckerTexture Vector<0 Scale=4 Fac>1;\n"
    "Mix A=(0.9, 0.2, 0.1) B=(0.2, 0.9, 0.3) Factor<1 Out>2;\n"
    "PrincipledOutput BaseColor<2 Roughness=0.3 CyclesPrincipled=1;\n"
    "PrincipledLayers BaseColor<2 Roughness=0.3 Sheen<1 SheenTint=1 Clearcoat<1 "
    "ClearcoatRoughness=0.1 Transmission<1 TransmissionRoughness=0.2 IOR=1.5;\n";

// The Diffuse lobe about a normal of its own (a constant one: the graph stays uv-only, so it
// is cached whole and the lobes' normals go through the entries, kCacheOutputLobeNormals).
// kLobesGraph is the same without it.
const char* const kLobeNormalGraph =
    "material Lobes;\n"
    "UVInput Out>0;\n"
    "CheckerTexture Vector<0 Scale=4 Fac>1;\n"
    "MixShader Fac<1 WeightA>2 WeightB>3;\n"
    "DiffuseBsdf Color=(0.9, 0.2, 0.1) Weight<2 Normal=(0.8660254, 0.5, 0);\n"
    "GlossyBsdf Color=(0.2, 0.9, 0.3) Roughness=0.3 Weight<3;\n";

const char* const kChosenPrincipledGraph =
    "material Lobes;\n"
    "UVInput Out>0;\n"
    "CheckerTexture Vector<0 Scale=4 Fac>1;\n"
    "MixShader Fac<1 WeightA>2 WeightB>3;\n"
    "ChooseShader WeightA<2 WeightB<3 ChosenA>4 ChosenB>5;\n"
    "PrincipledBsdf BaseColor=(0.9, 0.2, 0.1) Roughness=0.3 Sheen=1 Clearcoat=1 "
    "Transmission=0.5 Layers=7 Weight<4;\n"
    "PrincipledBsdf BaseColor=(0.2, 0.9, 0.3) Metallic=1 Roughness=0.3 Sheen=1 Clearcoat=1 "
    "Layers=7 Weight<5;\n";

// The same checker through the Principled outputs: the cache's own difference, for scale.
const char* const kPrincipledGraph =
    "material Lobes;\n"
    "UVInput Out>0;\n"
    "CheckerTexture Vector<0 Scale=4 Fac>1;\n"
    "Mix A=(0.9, 0.2, 0.1) B=(0.2, 0.9, 0.3) Factor<1 Out>2;\n"
    "BaseColorOutput In<2;\n"
    "RoughnessOutput 0.3;\n";

// Under a white sky, or (sun) lit by one sun alone: then a convex sphere's pixels are its
// light samples, without the noise of the paths that find the sky.
RenderResult renderGraph(const char* graph, CacheMode mode, Backend backend, Shading shading,
                         std::uint32_t seed = 0, bool sun = false) {
  Scene scene;
  scene.meshes.push_back(testing::sphere(32));
  scene.materials.push_back({"Lobes", "", graph});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  if (sun) {
    Light light;
    light.type = LightType::Directional;
    light.direction = glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f));
    light.intensity = glm::vec3(3.0f);
    scene.lights.push_back(light);
  } else {
    scene.environment.constantRadiance = glm::vec3(1.0f);
  }
  scene.camera.position = {0, 0, 3};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 45.0f;
  RendererOptions options = cacheOptions(mode, backend);
  options.nodeLibraryDirectory.clear();  // the embedded library: nodes/bsdf.inc's sinks
  // A miss is evaluated at its texel's centre, so an entry holds the same lobes whichever hit
  // fills it first, and a run repeats its picture on a multithreaded device.
  options.cache.snapUv = true;
  options.shading = shading;
  RenderSettings settings;
  settings.width = settings.height = 24;
  settings.pathsPerPixel = 2;
  settings.raysPerPath = 3;
  settings.frames = 4;
  settings.seed = seed;
  return Renderer(options).render(scene, settings);
}

void expectCachedLikeUncached(Backend backend, Shading shading, const char* graph = kLobesGraph,
                              bool chosen = false) {
  RenderResult off = renderGraph(graph, CacheMode::None, backend, shading);
  RenderResult on = renderGraph(graph, CacheMode::Texel, backend, shading);
  double flip = meanFlip(off.image, on.image);
  // For scale: the cache's own difference on the checker through the Principled outputs, or
  // for a choice per hit (whose 8 paths a pixel are mostly noise) what another seed changes.
  double scale =
      chosen ? meanFlip(off.image, renderGraph(graph, CacheMode::None, backend, shading, 1).image)
             : meanFlip(renderGraph(kPrincipledGraph, CacheMode::None, backend, shading).image,
                        renderGraph(kPrincipledGraph, CacheMode::Texel, backend, shading).image);
  std::printf("lobes through the texel cache (%s, %s, %s): mean LDR-FLIP %.4f (%s %.4f)\n",
              on.stats.backend.c_str(), on.stats.materialDispatch.c_str(), on.stats.shading.c_str(),
              flip, chosen ? "another seed" : "Principled", scale);
  EXPECT_GT(on.stats.frames.back().cacheLookups, 0u);
  // Red comes from the diffuse lobe, green mostly from the glossy one: a lost or misplaced
  // lobe changes the sphere's colour, far beyond the checker edges' quantisation.
  // With snapped misses a run repeats its figures. Measured on lavapipe: 0.1321 against a scale
  // of 0.1236 (both megakernels and the wavefront), 0.1280 (the layered Principled graph),
  // 0.1216 against another seed's 0.1166 (the choice per hit); so 0.02 over the scale. The
  // channel means: at most 0.0347 apart (the layered graph's green), so 0.04.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(testing::meanChannel(on.image, c, 6, 6, 18, 18),
                testing::meanChannel(off.image, c, 6, 6, 18, 18), 0.04)
        << "channel " << c;
  EXPECT_LT(flip, scale + 0.02);
}

TEST(BsdfLobesCache, CachedLobesRenderLikeUncachedInTheMegakernel) {
  expectCachedLikeUncached(Backend::RayQuery, Shading::Megakernel);
}

TEST(BsdfLobesCache, CachedLobesRenderLikeUncachedWithCallables) {
  expectCachedLikeUncached(Backend::RayTracingPipeline, Shading::Megakernel);
}

TEST(BsdfLobesCache, CachedLobesRenderLikeUncachedInTheWavefront) {
  expectCachedLikeUncached(Backend::RayQuery, Shading::Wavefront);
}

TEST(BsdfLobesCache, CachedPrincipledLayersRenderLikeUncachedInTheWavefront) {
  expectCachedLikeUncached(Backend::RayQuery, Shading::Wavefront, kPrincipledLayersGraph);
}

TEST(BsdfLobesCache, CachedChoiceRendersLikeUncachedInTheWavefront) {
  expectCachedLikeUncached(Backend::RayQuery, Shading::Wavefront, kChosenPrincipledGraph, true);
}

// Lit by one sun, the cached and uncached images of kLobeNormalGraph differ by the checker's
// texel quantisation alone, while its Diffuse lobe about the material's normal (kLobesGraph,
// what a cache that lost the lobes' normals would give) is far brighter in red (the
// Diffuse's colour) where the constant normal turns away from the sun. Measured on lavapipe:
// red 0.1257 cached, 0.1207 uncached, 0.4535 about the material's normal, so 0.02 either
// side.
void expectCachedLobeNormals(Shading shading) {
  Backend backend = Backend::RayQuery;
  RenderResult off = renderGraph(kLobeNormalGraph, CacheMode::None, backend, shading, 0, true);
  RenderResult on = renderGraph(kLobeNormalGraph, CacheMode::Texel, backend, shading, 0, true);
  RenderResult lost = renderGraph(kLobesGraph, CacheMode::None, backend, shading, 0, true);
  double redOff = testing::meanChannel(off.image, 0, 6, 6, 18, 18);
  double redOn = testing::meanChannel(on.image, 0, 6, 6, 18, 18);
  double redLost = testing::meanChannel(lost.image, 0, 6, 6, 18, 18);
  std::printf(
      "lobe normals through the texel cache (%s): red %.4f cached, %.4f uncached, "
      "%.4f about the material's normal\n",
      on.stats.shading.c_str(), redOn, redOff, redLost);
  EXPECT_GT(on.stats.frames.back().cacheLookups, 0u);
  EXPECT_NEAR(redOn, redOff, 0.02);
  EXPECT_GT(std::abs(redLost - redOff), 0.05);
}

TEST(BsdfLobesCache, CachedLobeNormalsRenderLikeUncachedInTheMegakernel) {
  expectCachedLobeNormals(Shading::Megakernel);
}

TEST(BsdfLobesCache, CachedLobeNormalsRenderLikeUncachedInTheWavefront) {
  expectCachedLobeNormals(Shading::Wavefront);
}

}  // namespace
}  // namespace memograph::runtime
