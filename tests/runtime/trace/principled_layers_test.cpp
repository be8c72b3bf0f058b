// White furnace for the Principled BSDF's sheen and clearcoat layers (nodes/bsdf.inc
// PrincipledLayers; runtime/shaders/common/bsdf_lobes.glsl): a large plane seen at 75 degrees
// from its normal through a narrow lens, under a uniform white sky, so that every pixel is
// the layer's directional albedo at that view angle (an open plane: every reflected ray sees
// the sky). The Principled outputs are black with Specular 0, so the Principled lobe adds
// nothing and the layer is seen alone. The expected albedos are the layers' formulas
// integrated numerically over the hemisphere (quoted below), so a sampler that does not draw
// what its density says, or a lost weight, moves the mean out of the band. A third test pins
// that the Principled lobe, with no layer, renders what the same Principled outputs render
// without lobes (brdf.glsl through bsdf_lobes.glsl). In both architectures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

const char* const kBlackPrincipled =
    "PrincipledOutput BaseColor=(0, 0, 0) Specular=0 CyclesPrincipled=1;\n";

RenderResult renderPlaneUnderWhiteSky(const std::string& graph, Shading shading) {
  Scene scene;
  scene.meshes.push_back(testing::quad(400.0f));
  scene.materials.push_back({"Layers", "", "material Layers;\n" + graph});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.environment.constantRadiance = glm::vec3(1.0f);
  // 75 degrees from the plane's normal (+y): 15 degrees above the plane.
  const float elevation = 15.0f * 3.14159265f / 180.0f;
  scene.camera.position = {0.0f, 3.0f * std::sin(elevation), 3.0f * std::cos(elevation)};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 4.0f;  // view angles within 2 degrees of 75
  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory.clear();  // the embedded library: nodes/bsdf.inc's sinks
  options.shading = shading;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 24;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 3;
  settings.frames = 8;
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  return result;
}

class PrincipledLayers : public ::testing::TestWithParam<Shading> {};

// A layer alone (the base black) on the plane: each channel's mean is its albedo at 75 degrees.
void expectLayerAlbedo(const std::string& layer, const char* name, double expected,
                       double tolerance, Shading shading) {
  RenderResult result = renderPlaneUnderWhiteSky(std::string(kBlackPrincipled) + layer, shading);
  for (int channel = 0; channel < 3; ++channel) {
    double mean = testing::meanChannel(result.image, channel, 0, 0, 24, 24);
    std::printf("%s albedo at 75 degrees (%s) channel %d: %.4f\n", name, shadingName(shading),
                channel, mean);
    EXPECT_NEAR(mean, expected, tolerance) << name << ", channel " << channel;
  }
}

// Cycles' sheen f cos = (1 - wi.h)^5 cos(theta_i) integrates to 0.0395 at 75 degrees (0.0351
// at 73, 0.0443 at 77; at most 0.087 at grazing, 0.0003 head-on: far below 1). Its
// cosine-weighted samples each weigh pi (1 - wi.h)^5 (measured 0.0398 in the megakernel and
// the wavefront alike): within 0.004.
TEST_P(PrincipledLayers, SheenAloneReflectsItsAlbedo) {
  expectLayerAlbedo("PrincipledLayers BaseColor=(0, 0, 0) Sheen=1 SheenTint=0;\n", "sheen", 0.0395,
                    0.004, GetParam());
}

// Clearcoat 4 makes the clearcoat lobe's weight 0.25 x 4 = 1. Its GTR1 (Roughness 0.5: alpha
// 0.25) with the Fresnel of IOR 1.5 and the shadowing of alpha 0.25 integrates to 0.1015 at
// 75 degrees (0.0920 at 73, 0.1127 at 77; 0.0295 head-on, 0.265 at grazing: below 1)
// (measured 0.1012 in both architectures): within 0.006.
TEST_P(PrincipledLayers, ClearcoatAloneReflectsItsAlbedo) {
  expectLayerAlbedo("PrincipledLayers BaseColor=(0, 0, 0) Clearcoat=4 ClearcoatRoughness=0.5;\n",
                    "clearcoat", 0.1015, 0.006, GetParam());
}

// The Principled lobe is brdf.glsl's BRDF: with Sheen and Clearcoat 0 the material renders
// as the same Principled outputs without lobes: the lobe, picked with probability 1, draws
// the same numbers as brdf.glsl does (measured equal to 4 digits, (0.8796, 0.6044, 0.3293));
// within 0.01, what two independent estimates over 18432 paths would allow.
TEST_P(PrincipledLayers, PrincipledLobeRendersAsThePrincipledOutputs) {
  const std::string principled =
      "PrincipledOutput BaseColor=(0.8, 0.5, 0.2) Metallic=0.3 Roughness=0.4 "
      "CyclesPrincipled=1;\n";
  RenderResult plain = renderPlaneUnderWhiteSky(principled, GetParam());
  RenderResult lobes = renderPlaneUnderWhiteSky(
      principled + "PrincipledLayers BaseColor=(0.8, 0.5, 0.2) Metallic=0.3;\n", GetParam());
  for (int channel = 0; channel < 3; ++channel) {
    double a = testing::meanChannel(plain.image, channel, 0, 0, 24, 24);
    double b = testing::meanChannel(lobes.image, channel, 0, 0, 24, 24);
    std::printf("Principled at 75 degrees (%s) channel %d: outputs %.4f, lobe %.4f\n",
                shadingName(GetParam()), channel, a, b);
    EXPECT_NEAR(a, b, 0.01) << "channel " << channel;
  }
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, PrincipledLayers,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

}  // namespace
}  // namespace memograph::runtime
