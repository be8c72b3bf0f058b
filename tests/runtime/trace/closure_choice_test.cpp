// Mix and Add Shader chosen per hit (nodes/bsdf.inc ChooseShader, PrincipledBsdf;
// docs/design/closures.md "Choosing a shader per hit"). ChooseShader's probability and
// weights are pinned through an emissive plane the camera sees (no bounce), and the mixed
// BSDF of two Principled BSDFs (two sets of Principled outputs, and with every layer eight
// lobes, twice MG_MAX_LOBES) in a white furnace: a large plane seen at 75 degrees under a
// uniform white sky, every pixel the material's directional albedo there. The mix must render
// the Fac-weighted sum of what each Principled BSDF renders alone through today's nodes
// (PrincipledOutput and PrincipledLayers, no choice). In both architectures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

constexpr int kSize = 24;

// Planes of the given graphs, 1000 apart along x in the plane y = 0 (so that no ray leaving one
// reaches another), under a uniform sky, and the camera looking at plane `look` 75 degrees
// from its normal through a narrow lens. One scene for several graphs: one shader to compile
// (the switch holds them all) whichever plane is looked at.
RenderResult renderPlane(const std::vector<std::string>& graphs, std::size_t look, Shading shading,
                         float sky, int frames, Backend backend = Backend::RayQuery) {
  Scene scene;
  scene.meshes.push_back(testing::quad(400.0f));
  for (std::size_t i = 0; i < graphs.size(); ++i) {
    const std::string name = "Choice" + std::to_string(i);
    scene.materials.push_back({name, "", "material " + name + ";\n" + graphs[i]});
    scene.instances.push_back(
        {0, std::uint32_t(i), glm::translate(glm::mat4(1.0f), glm::vec3(1000.0f * i, 0, 0))});
  }
  scene.environment.constantRadiance = glm::vec3(sky);
  // 75 degrees from the plane's normal (+y): 15 degrees above the plane.
  const float elevation = 15.0f * 3.14159265f / 180.0f;
  const float x = 1000.0f * float(look);
  scene.camera.position = {x, 3.0f * std::sin(elevation), 3.0f * std::cos(elevation)};
  scene.camera.target = {x, 0, 0};
  scene.camera.verticalFovDegrees = 4.0f;
  RendererOptions options = testing::testOptions(backend);
  options.nodeLibraryDirectory.clear();  // the embedded library: nodes/bsdf.inc
  options.shading = shading;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 3;
  settings.frames = frames;
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  return result;
}

// Plastic red with a clearcoat and a sheen, and rough gold metal: as today's single-Principled
// materials, and as PrincipledBsdf sinks of a Mix Shader (Fac 0.35) through ChooseShader.
const char* const kRedPlastic =
    "PrincipledOutput BaseColor=(0.8, 0.1, 0.05) Metallic=0 Roughness=0.3 CyclesPrincipled=1;\n"
    "PrincipledLayers BaseColor=(0.8, 0.1, 0.05) Metallic=0 Roughness=0.3 Sheen=1 "
    "Clearcoat=1 ClearcoatRoughness=0.1;\n";
const char* const kGold =
    "PrincipledOutput BaseColor=(1.0, 0.75, 0.3) Metallic=1 Roughness=0.5 CyclesPrincipled=1;\n"
    "PrincipledLayers BaseColor=(1.0, 0.75, 0.3) Metallic=1 Roughness=0.5 Sheen=0.5 "
    "Clearcoat=0.5;\n";
const char* const kMixedSinks =
    "PrincipledBsdf BaseColor=(0.8, 0.1, 0.05) Metallic=0 Roughness=0.3 Sheen=1 Clearcoat=1 "
    "ClearcoatRoughness=0.1 Layers=7 Weight<3;\n"
    "PrincipledBsdf BaseColor=(1.0, 0.75, 0.3) Metallic=1 Roughness=0.5 Sheen=0.5 "
    "Clearcoat=0.5 Layers=7 Weight<4;\n";

// The planes of the choice tests, one scene (one shader): ChooseShader(WeightA 0.5, WeightB
// 1.5) seen as emission (red: ChosenA, green: ChosenA + ChosenB, blue: ChosenB), an even
// choice (red ChosenA, green ChosenB), both under a black sky, and the eight-lobe mix of the
// two Principled BSDFs, under a white one.
const std::vector<std::string> kChoicePlanes = {
    "ChooseShader WeightA=0.5 WeightB=1.5 Stream=3 ChosenA>1 ChosenB>2;\n"
    "Add A<1 B<2 Out>3;\n"
    "CombineXYZ X<1 Y<3 Z<2 Vector>4;\n"
    "EmissionOutput Color<4 Strength=1;\n"
    "BaseColorOutput In=(0, 0, 0);\n"
    "SpecularOutput In=0;\n",
    "ChooseShader WeightA=1 WeightB=1 ChosenA>1 ChosenB>2;\n"
    "CombineXYZ X<1 Y<2 Z=0 Vector>4;\n"
    "EmissionOutput Color<4 Strength=1;\n"
    "BaseColorOutput In=(0, 0, 0);\n"
    "SpecularOutput In=0;\n",
    std::string("MixShader Fac=0.35 WeightA>1 WeightB>2;\n"
                "ChooseShader WeightA<1 WeightB<2 ChosenA>3 ChosenB>4;\n") +
        kMixedSinks};

class ClosureChoice : public ::testing::TestWithParam<Shading> {};

// ChooseShader(WeightA 0.5, WeightB 1.5) picks A with probability 0.25 and gives the chosen
// side 2, the other 0. Seen as emission (kChoicePlanes[0]), every sample's green is
// exactly 2, and red's mean over the 24 x 24 pixels' 32
// samples each (18432 choices) is 2 x 0.25 = 0.5, its standard error 2 sqrt(0.25 x 0.75 /
// 18432) = 0.0064: within 0.03. The sky is black, so nothing else adds light.
TEST_P(ClosureChoice, PicksBySideWeightAndGivesTheChosenSideBoth) {
  RenderResult result = renderPlane(kChoicePlanes, 0, GetParam(), 0.0f, 8);
  const auto channel = [&](int c) {
    return testing::meanChannel(result.image, c, 0, 0, kSize, kSize);
  };
  std::printf("ChooseShader (%s): mean ChosenA %.4f, ChosenA + ChosenB %.6f, ChosenB %.4f\n",
              shadingName(GetParam()), channel(0), channel(1), channel(2));
  EXPECT_NEAR(channel(0), 0.5, 0.03);
  EXPECT_NEAR(channel(2), 1.5, 0.03);
  EXPECT_NEAR(channel(1), 2.0, 1e-5);
}

// The albedo at 75 degrees of each channel of plane `look`'s material.
struct Albedo {
  double rgb[3];
};

Albedo albedoOf(const std::vector<std::string>& graphs, std::size_t look, Shading shading) {
  RenderResult result = renderPlane(graphs, look, shading, 1.0f, 16);
  Albedo a{};
  for (int c = 0; c < 3; ++c)
    a.rgb[c] = testing::meanChannel(result.image, c, 0, 0, kSize, kSize);
  return a;
}

// Each side alone renders its albedo through 36864 paths (24 x 24 pixels, 4 paths, 16
// frames); the mix draws one side per hit, so its estimate has the two sides' variance plus
// the choice's: the red channel's albedos (about 1.09 and 0.85) differ by 0.24, which adds
// about 0.24 x sqrt(0.35 x 0.65 / 36864) = 0.0006 of standard error. Measured within 0.004 of
// the weighted sum: within 0.015 (a mix that kept only one side, or both at full weight,
// misses by 0.1 or more).
//
// Then a Mix of (that Mix) and a white smooth Glass, which on the open plane under the white
// sky passes or reflects all light (albedo 1): two choices, nested, each with its own stream.
// Expected 0.6 x (0.65 red + 0.35 gold) + 0.4; measured within 0.005: within 0.02.
TEST_P(ClosureChoice, MixesOfTwoLayeredPrincipledRenderTheMixedAlbedo) {
  const std::vector<std::string> graphs = {
      kRedPlastic, kGold,
      std::string("MixShader Fac=0.35 WeightA>1 WeightB>2;\n"
                  "ChooseShader WeightA<1 WeightB<2 ChosenA>3 ChosenB>4;\n") +
          kMixedSinks,
      std::string("MixShader Fac=0.4 WeightA>10 WeightB>11;\n"
                  "ChooseShader WeightA<10 WeightB<11 Stream=0 ChosenA>12 ChosenB>13;\n"
                  "GlassBsdf Color=(1, 1, 1) Roughness=0 IOR=1.45 Weight<13;\n"
                  "MixShader Fac=0.35 Weight<12 WeightA>1 WeightB>2;\n"
                  "ChooseShader WeightA<1 WeightB<2 Stream=1 ChosenA>3 ChosenB>4;\n") +
          kMixedSinks};
  const Albedo red = albedoOf(graphs, 0, GetParam());
  const Albedo gold = albedoOf(graphs, 1, GetParam());
  const Albedo mixed = albedoOf(graphs, 2, GetParam());
  const Albedo nested = albedoOf(graphs, 3, GetParam());
  for (int c = 0; c < 3; ++c) {
    const double expected = 0.65 * red.rgb[c] + 0.35 * gold.rgb[c];
    std::printf(
        "Mix(red plastic, gold) at 75 degrees (%s) channel %d: red %.4f, gold %.4f, "
        "expected %.4f, mixed %.4f\n",
        shadingName(GetParam()), c, red.rgb[c], gold.rgb[c], expected, mixed.rgb[c]);
    EXPECT_NEAR(mixed.rgb[c], expected, 0.015) << "channel " << c;
    const double expectedNested = 0.6 * expected + 0.4;
    std::printf("Mix(Mix(red plastic, gold), glass) (%s) channel %d: expected %.4f, mixed %.4f\n",
                shadingName(GetParam()), c, expectedNested, nested.rgb[c]);
    EXPECT_NEAR(nested.rgb[c], expectedNested, 0.02) << "channel " << c;
  }
}

// A lobe about its own normal takes an unchosen shader's slot as any lobe does: a Mix of the
// four-lobe red plastic and a white smooth Glass about the plane's own normal (+y, so its
// picture is the Glass's without a normal: albedo 1), chosen per hit, renders 0.65 x red +
// 0.35. The Glass, added when the Principled's four lobes fill the slots, would otherwise be
// lost where it is chosen (0.65 x red alone, 0.35 lower).
TEST_P(ClosureChoice, AChosenLobeAboutItsOwnNormalTakesAnUnchosenSlot) {
  const std::vector<std::string> graphs = {
      kRedPlastic,
      "MixShader Fac=0.35 WeightA>1 WeightB>2;\n"
      "ChooseShader WeightA<1 WeightB<2 ChosenA>3 ChosenB>4;\n"
      "PrincipledBsdf BaseColor=(0.8, 0.1, 0.05) Metallic=0 Roughness=0.3 Sheen=1 Clearcoat=1 "
      "ClearcoatRoughness=0.1 Layers=7 Weight<3;\n"
      "GlassBsdf Color=(1, 1, 1) Roughness=0 IOR=1.45 Weight<4 Normal=(0, 1, 0);\n"};
  const Albedo red = albedoOf(graphs, 0, GetParam());
  const Albedo mixed = albedoOf(graphs, 1, GetParam());
  for (int c = 0; c < 3; ++c) {
    const double expected = 0.65 * red.rgb[c] + 0.35;
    std::printf(
        "Mix(red plastic, glass about its normal) (%s) channel %d: expected %.4f, "
        "mixed %.4f\n",
        shadingName(GetParam()), c, expected, mixed.rgb[c]);
    EXPECT_NEAR(mixed.rgb[c], expected, 0.02) << "channel " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, ClosureChoice,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

// At one seed the two architectures, and the pipeline backend's callables, draw the same
// choices: the emissive choice pattern is the same image, pixel for pixel.
TEST(ClosureChoiceArchitectures, MegakernelWavefrontAndCallablesChooseAlike) {
  RenderResult mega = renderPlane(kChoicePlanes, 1, Shading::Megakernel, 0.0f, 1);
  RenderResult wave = renderPlane(kChoicePlanes, 1, Shading::Wavefront, 0.0f, 1);
  ASSERT_EQ(mega.image.rgba.size(), wave.image.rgba.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < mega.image.rgba.size(); ++i)
    largest = std::max(largest, double(std::abs(mega.image.rgba[i] - wave.image.rgba[i])));
  std::printf("largest per-pixel difference megakernel vs wavefront: %g\n", largest);
  EXPECT_LT(largest, 1e-5);
  // The ray-tracing pipeline (the GPU's backend) with a callable shader per material, whose
  // callables are compiled with the choice's mg_addLobe too: the same picks.
  RenderResult callable =
      renderPlane(kChoicePlanes, 1, Shading::Megakernel, 0.0f, 1, Backend::RayTracingPipeline);
  EXPECT_EQ(callable.stats.materialDispatch, "callable");
  double largestCallable = 0.0;
  for (std::size_t i = 0; i < mega.image.rgba.size(); ++i)
    largestCallable =
        std::max(largestCallable, double(std::abs(mega.image.rgba[i] - callable.image.rgba[i])));
  std::printf("largest per-pixel difference megakernel vs callables: %g\n", largestCallable);
  EXPECT_LT(largestCallable, 1e-5);
  // Not the same pick everywhere: the pixels' choices differ.
  const double red = testing::meanChannel(mega.image, 0, 0, 0, kSize, kSize);
  EXPECT_GT(red, 0.5);
  EXPECT_LT(red, 1.5);
}

// The callables of the pipeline backend compile mg_addLobe with the choice too
// (MG_CLOSURE_CHOICE): the eight-lobe mix renders there as in the query backend's megakernel.
TEST(ClosureChoiceArchitectures, CallablesRenderTheEightLobeMixAlike) {
  RenderResult query = renderPlane(kChoicePlanes, 2, Shading::Megakernel, 1.0f, 2);
  RenderResult callable =
      renderPlane(kChoicePlanes, 2, Shading::Megakernel, 1.0f, 2, Backend::RayTracingPipeline);
  for (int c = 0; c < 3; ++c) {
    const double a = testing::meanChannel(query.image, c, 0, 0, kSize, kSize);
    const double b = testing::meanChannel(callable.image, c, 0, 0, kSize, kSize);
    std::printf("eight-lobe mix, channel %d: query %.5f, callables %.5f\n", c, a, b);
    EXPECT_NEAR(a, b, 1e-4) << "channel " << c;
  }
}

}  // namespace
}  // namespace memograph::runtime
