// Emitters whose emission NEE must take from their graphs (MG_NEE_EVALUATES_EMISSION): the
// wavefront evaluates a light sample's point in its emitter's material pass after the shadow
// pass, where the megakernel evaluates it in place (sampleDirectLight). Both draw the same
// random numbers, so at one seed they give the same picture, up to the compilers' rounding
// (1e-4 of a pixel's value, as Wavefront.AtOneSeedTheMegakernelTracesTheSamePaths states).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/renderer.h"

namespace memograph::runtime {
namespace {

// A grey floor under a 1 m emissive panel at height 1.5 facing down (lighting the floor) or up
// (the floor behind it), its emission its graph's (EmissionKind::Graph: NEE evaluates it at
// the sampled point).
Scene panelScene(const std::string& emitterBody, bool facingDown) {
  Scene scene;
  scene.meshes.push_back(testing::quad(6.0f));
  scene.meshes.push_back(testing::quad(1.0f));
  scene.materials.push_back(
      {"Floor", "",
       "material Floor;\nBaseColorOutput In=(0.5, 0.5, 0.5);\nRoughnessOutput In=1;\n"});
  MaterialRef panel;
  panel.name = "Panel";
  panel.graphText = "material Panel;\n" + emitterBody + "BaseColorOutput In=(0, 0, 0);\n";
  panel.emissionEstimate = glm::vec3(5.0f);
  panel.emissionKind = MaterialRef::EmissionKind::Graph;
  scene.materials.push_back(panel);
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  glm::mat4 place = glm::translate(glm::mat4(1.0f), {0.0f, 1.5f, 0.0f});
  if (facingDown)
    place = glm::rotate(place, glm::radians(180.0f), glm::vec3(1, 0, 0));
  scene.instances.push_back({1, 1, place});
  scene.camera.position = {0, 1.0f, 4.0f};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 50.0f;
  return scene;
}

// `pathSlots` > 0: the wavefront's rounds in chunks of that many pixels. `cache`: the texel
// cache (its voxel keys never refreshed, so both architectures keep every entry they insert).
RenderResult renderPanel(const Scene& scene, Backend backend, Shading shading,
                         std::uint32_t pathSlots = 0, CacheMode cache = CacheMode::None) {
  RendererOptions options = testing::testOptions(backend);
  options.nodeLibraryDirectory.clear();  // the embedded library
  options.shading = shading;
  options.wavefrontPaths = pathSlots;
  options.cache.mode = cache;
  options.cache.refreshFrames = 0;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 2;  // NEE at the floor, and the BSDF ray that finds the panel (MIS)
  settings.frames = 2;
  settings.seed = 7;
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  EXPECT_EQ(result.stats.shading, shadingName(shading));
  return result;
}

double largestRelativeDifference(const HdrImage& a, const HdrImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
    const double scale = std::max({1.0, std::abs(double(a.rgba[i])), std::abs(double(b.rgba[i]))});
    largest = std::max(largest, std::abs(double(a.rgba[i]) - double(b.rgba[i])) / scale);
  }
  return largest;
}

// A checker over the panel's world position (the point's position must be the one sampled)
// and an emission on the front face only, the panel facing the floor or away from it (the
// point must be seen from the shading point along the sample's direction: from behind it
// emits nothing), on both backends (the pipeline's megakernel evaluates in a callable). Fails
// where the wavefront drops the points' emission, takes another point's or another
// direction's, or refuses the scene (measured: a constant emission of 5 in place of the
// graph's moved pixels by 0.125 in the checker case).
TEST(WavefrontEmitterNee, EmittersGraphsAtLightSamplesGiveTheMegakernelsPicture) {
  const char* frontOnly =
      "BackfacingInput Out>0;\n"
      "Math Value=1 Value1<0 Value2=0 Operation=1 UseClamp=0 Result>1;\n"
      "EmissionOutput Color=(5, 5, 5) Strength<1;\n";
  const struct {
    const char* name;
    const char* body;
    bool facingDown;
  } emitters[] = {
      {"checker",
       "PositionInput Out>0;\n"
       "CheckerTexture Vector<0 Color1=(8, 8, 8) Color2=(1, 2, 4) Scale=4 Color>1;\n"
       "EmissionOutput Color<1 Strength=1;\n",
       true},
      {"front only, facing the floor", frontOnly, true},
      {"front only, facing away", frontOnly, false},
  };
  for (const auto& emitter : emitters) {
    for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
      const std::string what =
          std::string(emitter.name) + ", " + (backend == Backend::RayQuery ? "query" : "pipeline");
      SCOPED_TRACE(what);
      const Scene scene = panelScene(emitter.body, emitter.facingDown);
      const RenderResult megakernel = renderPanel(scene, backend, Shading::Megakernel);
      const RenderResult wavefront = renderPanel(scene, backend, Shading::Wavefront);
      const double floorLight = testing::meanChannel(wavefront.image, 0, 0, 12, 16, 16);
      const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
      std::printf("%s: floor %.4f, largest relative difference %.3g\n", what.c_str(), floorLight,
                  difference);
      if (emitter.facingDown) {
        EXPECT_GT(floorLight, 0.01) << "the panel lights the floor";
      } else {
        EXPECT_LT(floorLight, 1e-6) << "the panel's back emits nothing";
      }
      EXPECT_LT(difference, 1e-4);
      EXPECT_EQ(wavefront.stats.frames.back().rays, megakernel.stats.frames.back().rays);
      // One copy of its graph a material pass: the panel's pass evaluates its hits and its
      // light points through one call (two copies before), the floor's no points at all.
      EXPECT_EQ(wavefront.stats.wavefrontMaterialPasses, 2u);
      EXPECT_EQ(wavefront.stats.wavefrontMaterialGraphCopiesMax, 1u);
    }
  }
}

// Transparent shadows (transparent_shadow.glsl) on the light points' route: a tinted
// Transparent plane between the panel and the floor. The shadow pass evaluates the plane's
// graph where its rays cross it and queues the point with its contribution tinted, the
// emitter's pass then multiplies in the emission: the megakernel's picture, and the same
// rays (each segment past the plane counted). Fails where the tint is dropped on the way to
// the light points' pass (the floor under the plane then as bright as without it).
TEST(WavefrontEmitterNee, LightPointsThroughATransparentPlaneGiveTheMegakernelsPicture) {
  const std::string checker =
      "PositionInput Out>0;\n"
      "CheckerTexture Vector<0 Color1=(8, 8, 8) Color2=(1, 2, 4) Scale=4 Color>1;\n"
      "EmissionOutput Color<1 Strength=1;\n";
  const Scene open = panelScene(checker, true);
  Scene shaded = open;
  shaded.meshes.push_back(testing::quad(1.5f));
  shaded.materials.push_back(
      {"Tinted", "", "material Tinted;\nTransparentBsdf Color=(0.9, 0.6, 0.3);\n"});
  shaded.instances.push_back({2, 2, glm::translate(glm::mat4(1.0f), {0.0f, 0.75f, 0.0f})});
  const RenderResult megakernel = renderPanel(shaded, Backend::RayQuery, Shading::Megakernel);
  const RenderResult wavefront = renderPanel(shaded, Backend::RayQuery, Shading::Wavefront);
  const RenderResult unshaded = renderPanel(open, Backend::RayQuery, Shading::Wavefront);
  const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
  // The floor in the middle of the image, beneath the plane (the camera sees it past the
  // plane's edge): its blue is the panel's light through the plane's 0.3.
  const double blue = testing::meanChannel(wavefront.image, 2, 6, 6, 10, 10);
  const double openBlue = testing::meanChannel(unshaded.image, 2, 6, 6, 10, 10);
  std::printf("floor blue %.4f (without the plane %.4f), largest relative difference %.3g\n", blue,
              openBlue, difference);
  EXPECT_LT(difference, 1e-4);
  EXPECT_EQ(wavefront.stats.frames.back().rays, megakernel.stats.frames.back().rays);
  EXPECT_GT(blue, 0.01);
  EXPECT_LT(blue, 0.7 * openBlue);
}

// A round split into chunks (a path state of 100 slots for 256 pixels) queues and evaluates
// each chunk's light points with its own passes: the same image bit for bit.
TEST(WavefrontEmitterNee, LightPointsOfARoundSplitIntoChunksGiveTheSameImage) {
  const Scene scene = panelScene(
      "PositionInput Out>0;\n"
      "CheckerTexture Vector<0 Color1=(8, 8, 8) Color2=(1, 2, 4) Scale=4 Color>1;\n"
      "EmissionOutput Color<1 Strength=1;\n",
      true);
  const RenderResult whole = renderPanel(scene, Backend::RayQuery, Shading::Wavefront);
  const RenderResult split = renderPanel(scene, Backend::RayQuery, Shading::Wavefront, 100);
  EXPECT_EQ(split.stats.wavefrontChunks, 3u);
  EXPECT_EQ(whole.image.rgba, split.image.rgba);
  EXPECT_GT(testing::meanChannel(split.image, 0, 0, 12, 16, 16), 0.01);
}

// An emitter keyed by its cut (a checker over its world position, the cut, mixed towards grey
// by Layer Weight per ray, the rest) with the texel cache: a hit on the panel hands its cut's
// values to the shade pass, which runs the rest, while a light point on it runs the rest in
// the panel's material pass and adds its emission there (MG_MATERIAL_REST_IN_SHADE with
// MG_MATERIAL_LIGHT_POINTS). The cached megakernel's picture, on both backends: on the query
// backend its hits read the same entries; on the pipeline backend its callables key no cut
// and evaluate the panel at each hit, which a checker's cell makes the same value. Its light
// points evaluate uncached, as the wavefront's. Fails where either route drops the values,
// runs another graph's rest or skips the light points.
TEST(WavefrontEmitterNee, ACutEmittersHitsAndLightPointsGiveTheCachedMegakernelsPicture) {
  const Scene scene = panelScene(
      "PositionInput Out>0;\n"
      "CheckerTexture Vector<0 Color1=(8, 8, 8) Color2=(1, 2, 4) Scale=4 Color>1;\n"
      "LayerWeight Facing>2;\n"
      "MixColor Factor<2 A<1 B=(0.5, 0.5, 0.5) Result>3;\n"
      "EmissionOutput Color<3 Strength=1;\n",
      true);
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    SCOPED_TRACE(backend == Backend::RayQuery ? "query" : "pipeline");
    const RenderResult megakernel =
        renderPanel(scene, backend, Shading::Megakernel, 0, CacheMode::Texel);
    const RenderResult wavefront =
        renderPanel(scene, backend, Shading::Wavefront, 0, CacheMode::Texel);
    const FrameStats& last = wavefront.stats.frames.back();
    const double floorLight = testing::meanChannel(wavefront.image, 0, 0, 12, 16, 16);
    const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
    std::printf(
        "%s: %llu lookups, %llu hits (megakernel %llu, %llu); floor %.4f, largest "
        "relative difference %.3g\n",
        backend == Backend::RayQuery ? "query" : "pipeline", (unsigned long long)last.cacheLookups,
        (unsigned long long)last.cacheHits,
        (unsigned long long)megakernel.stats.frames.back().cacheLookups,
        (unsigned long long)megakernel.stats.frames.back().cacheHits, floorLight, difference);
    EXPECT_GT(last.cacheHits, 0u) << "the panel's hits read its cut's entries";
    EXPECT_GT(megakernel.stats.frames.back().cacheHits, 0u);
    EXPECT_GT(floorLight, 0.01) << "the panel's light points light the floor";
    EXPECT_LT(difference, 1e-4);
    EXPECT_EQ(last.rays, megakernel.stats.frames.back().rays);
  }
}

}  // namespace
}  // namespace memograph::runtime
