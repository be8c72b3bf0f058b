// Cycles' Filter Glossy (path_shading.glsl filterGlossy; Cycles 3.4 surface_shader.h
// surface_shader_prepare_closures, bsdf.h bsdf_blur): a glossy lobe found after a bounce of pdf
// p gets alpha >= sqrt(1 - p / F) / 2. Checked on a diffuse floor under a mirror ceiling lit by
// a point light between them: with a huge F every blur alpha is 1/2 (to 3e-7), so the mirror
// seen after the floor's diffuse bounce must light the floor exactly as a Glossy of alpha 1/2
// does, in both architectures; without the blur the mirror gives the point light nothing (a
// singular lobe evaluates to 0 for light sampling), so the floor would stay darker.
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/renderer.h"

namespace memograph::runtime {
namespace {

constexpr int kSize = 24;

// A white Diffuse floor (y = 0) and a Glossy ceiling (y = 2) of `roughness` and `distribution`
// (0 GGX, 2 Sharp), a point light at y = 1, and a camera at y = 1.5 looking down at the floor,
// which never sees the ceiling: every glossy hit comes after the floor's diffuse bounce.
Scene floorUnderCeiling(float roughness, int distribution = 0) {
  Scene scene;
  scene.meshes.push_back(testing::quad(40.0f));
  scene.materials = {
      {"Floor", "", "material Floor;\nDiffuseBsdf Color=(0.8, 0.8, 0.8);\n"},
      {"Ceiling", "",
       "material Ceiling;\nGlossyBsdf Color=(0.9, 0.9, 0.9) Roughness=" +
           std::to_string(roughness) + " Distribution=" + std::to_string(distribution) + ";\n"}};
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.instances.push_back({0, 1, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, 0.0f))});
  Light bulb;
  bulb.type = LightType::Point;
  bulb.position = {0.3f, 1.0f, -0.2f};
  bulb.intensity = glm::vec3(3.0f);
  scene.lights.push_back(bulb);
  scene.camera.position = {0.0f, 1.5f, 0.6f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 50.0f;
  return scene;
}

HdrImage renderWith(const Scene& scene, Shading shading, std::optional<float> filterGlossy) {
  RendererOptions o = testing::testOptions(Backend::RayQuery);
  o.nodeLibraryDirectory.clear();  // the real node library, which has the BSDF nodes
  o.shading = shading;
  o.filterGlossy = filterGlossy;
  RenderSettings settings;
  settings.width = kSize;
  settings.height = kSize;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 2;  // the floor's hit, then the ceiling's light sample
  settings.seed = 7;
  return Renderer(o).render(scene, settings).image;
}

double meanOf(const HdrImage& image) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c)
    sum += testing::meanChannel(image, c, 0, 0, kSize, kSize);
  return sum / 3.0;
}

// The mirror blurred by F = 1e6 traces the same paths as a Glossy of roughness sqrt(1/2) (alpha
// 1/2) without the blur: the same random numbers drive both, and alpha differs by 3e-7, so the
// pictures agree to float rounding. The unblurred mirror's floor is much darker, and so is a
// Sharp one's at the same F.
TEST(FilterGlossy, MirrorSeenAfterADiffuseBounceBlursToAlphaOneHalf) {
  const Scene mirror = floorUnderCeiling(0.0f);
  const Scene rough = floorUnderCeiling(std::sqrt(0.5f));
  for (Shading shading : {Shading::Megakernel, Shading::Wavefront}) {
    const char* name = shading == Shading::Megakernel ? "megakernel" : "wavefront";
    const HdrImage blurred = renderWith(mirror, shading, 1.0e6f);
    const HdrImage reference = renderWith(rough, shading, std::nullopt);
    const testing::RoundingDifference d = testing::roundingDifference(blurred, reference);
    std::printf("%s: mean %.5f blurred, %.5f alpha 1/2; largest difference %.3g\n", name,
                meanOf(blurred), meanOf(reference), d.largest);
    EXPECT_LE(d.largest, 1e-3 * d.referenceMean) << name;
    if (shading == Shading::Megakernel) {
      // Without the blur the mirror adds nothing to the floor through light sampling (the
      // architectures trace the same paths, so one of them shows it).
      const HdrImage unblurred = renderWith(mirror, shading, std::nullopt);
      const double unblurredMean = meanOf(unblurred);
      EXPECT_GT(meanOf(blurred), 1.05 * unblurredMean) << name;
      // Blender's Sharp distribution is Cycles' separate mirror closure, which bsdf_blur leaves
      // alone: the same huge F leaves it the unblurred mirror.
      const HdrImage sharp = renderWith(floorUnderCeiling(0.0f, 2), shading, 1.0e6f);
      const testing::RoundingDifference s = testing::roundingDifference(sharp, unblurred);
      std::printf("%s: mean %.5f unblurred, %.5f Sharp at F = 1e6; largest difference %.3g\n", name,
                  unblurredMean, meanOf(sharp), s.largest);
      EXPECT_LE(s.largest, 1e-5 * s.referenceMean) << name;
    }
  }
}

// F = 0 is off: the same picture, to the bit, as a render that never names it (the path tracer
// is then compiled without any of it); and a scene with no glossy lobe renders the same with
// the blur on, in both architectures (the path state's extra field moves nothing else).
TEST(FilterGlossy, OffOrWithoutGlossyLobesChangesNoPixel) {
  Scene diffuseOnly = floorUnderCeiling(0.0f);
  diffuseOnly.materials[1].graphText = "material Ceiling;\nDiffuseBsdf Color=(0.5, 0.5, 0.5);\n";
  for (Shading shading : {Shading::Megakernel, Shading::Wavefront}) {
    const char* name = shading == Shading::Megakernel ? "megakernel" : "wavefront";
    const HdrImage plain = renderWith(diffuseOnly, shading, std::nullopt);
    const HdrImage on = renderWith(diffuseOnly, shading, 1.0f);
    ASSERT_EQ(plain.rgba.size(), on.rgba.size());
    EXPECT_EQ(plain.rgba, on.rgba) << name;
    if (shading == Shading::Megakernel) {  // F = 0 is resolved on the host, alike for both
      EXPECT_EQ(plain.rgba, renderWith(diffuseOnly, shading, 0.0f).rgba) << name;
    }
  }
}

}  // namespace
}  // namespace memograph::runtime
