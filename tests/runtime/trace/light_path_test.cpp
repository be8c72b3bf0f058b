// Light Path's per-ray inputs (MaterialInputs rayFlags, rayLength and the depths;
// path_shading.glsl PathState) in both path-tracer architectures: a camera ray's hit sees
// exactly the camera's state, the megakernel and the wavefront carry the same state from
// bounce to bounce (the same picture at one seed), and the linker says whether any graph reads
// the state (else the shaders compile it out, MG_OMIT_PATH_INPUTS).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/materials/material_linker.h"
#include "runtime/renderer.h"
#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {
namespace {

// A diffuse-and-glossy surface whose emission encodes the path state: red 0.2 for camera
// rays plus 0.05 a bounce of Ray Depth; green 0.1 a diffuse bounce plus 0.3 on glossy rays;
// blue 0.1 a glossy bounce, 0.02 a metre of Ray Length and 0.2 on diffuse rays.
constexpr const char* kProbe =
    "material Probe;\n"
    "LightPath IsCameraRay>1 IsDiffuseRay>2 IsGlossyRay>3 RayLength>4 RayDepth>5 "
    "DiffuseDepth>6 GlossyDepth>7;\n"
    "MultiplyAdd A<5 B=0.05 C=0.0 Out>8;\n"
    "MultiplyAdd A<1 B=0.2 C<8 Out>10;\n"
    "MultiplyAdd A<6 B=0.1 C=0.0 Out>11;\n"
    "MultiplyAdd A<3 B=0.3 C<11 Out>12;\n"
    "MultiplyAdd A<7 B=0.1 C=0.0 Out>13;\n"
    "MultiplyAdd A<4 B=0.02 C<13 Out>14;\n"
    "MultiplyAdd A<2 B=0.2 C<14 Out>15;\n"
    "CombineXYZ X<10 Y<12 Z<15 Vector>16;\n"
    "EmissionOutput Color<16 Strength=1.0;\n"
    "BaseColorOutput In=(0.7, 0.7, 0.7);\n"
    "RoughnessOutput In=0.4;\n";

// A floor and a wall facing the camera, both Probe, under a constant sky; every pixel sees
// one of them.
Scene cornerScene() {
  Scene scene;
  scene.meshes.push_back(testing::quad(40.0f));
  scene.materials.push_back({"Probe", "", kProbe});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  glm::mat4 wall = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.0f)) *
                   glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
  scene.instances.push_back({0, 0, wall});
  scene.camera.position = {0.0f, 1.0f, 2.0f};
  scene.camera.target = {0.0f, 0.5f, -1.0f};
  scene.environment.constantRadiance = glm::vec3(0.5f);
  return scene;
}

RendererOptions options(Shading shading, Backend backend = Backend::RayQuery) {
  RendererOptions o = testing::testOptions(backend);
  o.nodeLibraryDirectory.clear();  // the real node library, which has LightPath
  o.shading = shading;
  return o;
}

RenderSettings settings(std::uint32_t bounces) {
  RenderSettings s;
  s.width = 16;
  s.height = 12;
  s.pathsPerPixel = 2;
  s.raysPerPath = bounces;
  s.frames = 1;
  s.seed = 7;
  return s;
}

// With one ray a path, every pixel is the emission at its camera ray's hit: Is Camera Ray 1,
// no bounce, no lobe, and Ray Length the hit's distance from the camera (blue / 0.02), which
// the corner keeps between 1 m (the camera's height over the floor) and 21 m (the far corner
// of the 40 m wall).
// The megakernel on the query backend (the switch) and on the pipeline backend (the
// material callables, whose payload carries the path state), and the wavefront.
TEST(LightPath, CameraRaysSeeTheCameraState) {
  struct Case {
    Shading shading;
    Backend backend;
    const char* name;
  };
  for (const Case& c :
       {Case{Shading::Megakernel, Backend::RayQuery, "megakernel, switch"},
        Case{Shading::Megakernel, Backend::RayTracingPipeline, "megakernel, callables"},
        Case{Shading::Wavefront, Backend::RayQuery, "wavefront"}}) {
    const HdrImage image =
        Renderer(options(c.shading, c.backend)).render(cornerScene(), settings(1)).image;
    double shortest = 1e30, longest = 0.0;
    for (std::uint32_t y = 0; y < image.height; ++y)
      for (std::uint32_t x = 0; x < image.width; ++x) {
        const float* p = image.pixel(x, y);
        EXPECT_NEAR(p[0], 0.2f, 1e-6) << x << "," << y;  // Is Camera Ray, Ray Depth 0
        EXPECT_EQ(p[1], 0.0f) << x << "," << y;          // no diffuse depth, not glossy
        shortest = std::min(shortest, p[2] / 0.02);
        longest = std::max(longest, p[2] / 0.02);
      }
    std::printf("%s: ray lengths %.3f to %.3f m\n", c.name, shortest, longest);
    EXPECT_GT(shortest, 1.0);
    EXPECT_LT(longest, 21.0);
    EXPECT_GT(longest, shortest + 1.0);  // the lengths are the hits', not one constant
  }
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

double meanOf(const HdrImage& image, int c) {
  return testing::meanChannel(image, c, 0, 0, int(image.width), int(image.height));
}

// Four rays a path: the bounces' hits see their depths and lobes. At one seed both
// architectures trace the same paths (rng.glsl), so the wavefront, which keeps the state in
// its path-state buffer between passes, must give the megakernel's picture; a state lost
// between bounces (the camera's again) would leave only the camera's red and the lengths.
TEST(LightPath, WavefrontCarriesTheMegakernelsPathState) {
  const HdrImage megakernel =
      Renderer(options(Shading::Megakernel)).render(cornerScene(), settings(4)).image;
  const HdrImage wavefront =
      Renderer(options(Shading::Wavefront)).render(cornerScene(), settings(4)).image;
  const HdrImage cameraOnly =
      Renderer(options(Shading::Megakernel)).render(cornerScene(), settings(1)).image;
  const double difference = largestRelativeDifference(megakernel, wavefront);
  std::printf(
      "megakernel mean (%.4f, %.4f, %.4f), wavefront (%.4f, %.4f, %.4f), largest "
      "relative difference %.3g\n",
      meanOf(megakernel, 0), meanOf(megakernel, 1), meanOf(megakernel, 2), meanOf(wavefront, 0),
      meanOf(wavefront, 1), meanOf(wavefront, 2), difference);
  EXPECT_LT(difference, 1e-4);
  // The bounces' own terms are there: green only comes from bounces (diffuse depth, glossy
  // rays), and red grows with the depth beyond the camera's 0.2 and the sky's share.
  EXPECT_GT(meanOf(megakernel, 1), 0.05);
  EXPECT_GT(meanOf(megakernel, 1), meanOf(cameraOnly, 1) + 0.05);
}

// A uv noise the camera sees and blue emission for every other ray: the noise is a uv cut,
// Light Path in the rest. With the texel cache keyed by the cut (MG_CACHE_CUTS), bounces look
// up the noise a camera ray may have cached and the rest still switches on their own state:
// the cached picture is the uncached one up to the noise's texel centres, and the bounces'
// blue (the floor lit by the wall and back) is there in both. Were Light Path cached with
// the noise, every bounce would see the camera's colour.
constexpr const char* kNoiseForTheCamera =
    "material ByRay;\n"
    "UVInput Out>1;\n"
    "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
    "LightPath IsCameraRay>3;\n"
    "MixColor Factor<3 A=(0.0, 0.0, 1.0) B<2 Result>4;\n"
    "EmissionOutput Color<4 Strength=1.0;\n"
    "BaseColorOutput In=(0.7, 0.7, 0.7);\n";

TEST(LightPath, TheTexelCacheKeepsLightPathOutOfItsEntries) {
  const LinkedMaterials linked = linkMaterials({{"ByRay", "", kNoiseForTheCamera}});
  ASSERT_EQ(linked.materials.at(0).cutDomain, gpu::kCacheCutUv);
  EXPECT_FALSE(linked.materials.at(0).cacheable);
  Scene scene = cornerScene();
  scene.materials = {{"ByRay", "", kNoiseForTheCamera}};
  scene.environment.constantRadiance = glm::vec3(0.0f);
  RenderSettings s = settings(3);
  s.width = 24;
  s.height = 18;
  RendererOptions cached = options(Shading::Megakernel);
  cached.cache.mode = CacheMode::Texel;
  cached.cache.entries = 1u << 16;
  const RenderResult off = Renderer(options(Shading::Megakernel)).render(scene, s);
  const RenderResult on = Renderer(cached).render(scene, s);
  const HdrImage cameraOnly = Renderer(cached).render(scene, settings(1)).image;
  const FrameStats& frame = on.stats.frames.back();
  std::printf(
      "uncached mean (%.4f, %.4f, %.4f), cached (%.4f, %.4f, %.4f), camera rays only "
      "blue %.4f; %llu lookups, hit rate %.2f %%\n",
      meanOf(off.image, 0), meanOf(off.image, 1), meanOf(off.image, 2), meanOf(on.image, 0),
      meanOf(on.image, 1), meanOf(on.image, 2), meanOf(cameraOnly, 2),
      (unsigned long long)frame.cacheLookups, 100.0 * frame.cacheHitRate());
  EXPECT_GT(frame.cacheLookups, 24u * 18u);  // the bounces' hits looked up too
  EXPECT_GT(frame.cacheHitRate(), 0.0);
  // At one seed both trace the same paths, so they differ per pixel only where a cached noise
  // was taken at its texel's centre: measured 0.0007 on lavapipe. With Light Path wrongly in
  // the cut (the path inputs classed constant) 0.0021: camera and bounce rays mostly key
  // different mip levels (their footprints differ), so they seldom share an entry. Bound
  // 0.0012.
  double difference = 0.0;
  for (std::size_t i = 0; i < on.image.rgba.size(); ++i)
    difference += std::abs(double(on.image.rgba[i]) - double(off.image.rgba[i]));
  difference /= double(on.image.rgba.size());
  std::printf("mean absolute difference cached vs uncached %.4f\n", difference);
  EXPECT_LT(difference, 0.0012);
  // The bounces' blue: more blue than the camera's own noise gives.
  EXPECT_GT(meanOf(on.image, 2), meanOf(cameraOnly, 2) + 0.05);
}

// The linker tells the renderer whether any graph reads the path state; without one the
// shaders define MG_OMIT_PATH_INPUTS and track none.
TEST(LightPath, LinkerSaysWhetherAnyGraphReadsThePathState) {
  MaterialLinkOptions link;
  link.nodeLibraryDirectory.clear();
  const MaterialRef plain{"Plain", "", "material Plain;\nBaseColorOutput In=(0.5, 0.5, 0.5);\n"};
  const MaterialRef probe{"Probe", "", kProbe};
  EXPECT_FALSE(linkMaterials({plain}, link).pathInputs);
  EXPECT_TRUE(linkMaterials({plain, probe}, link).pathInputs);
  EXPECT_FALSE(linkMaterials({plain}, link).objectInputs);
  EXPECT_FALSE(linkMaterials({probe}, link).objectInputs);  // the path state is not object space
}

}  // namespace
}  // namespace memograph::runtime
