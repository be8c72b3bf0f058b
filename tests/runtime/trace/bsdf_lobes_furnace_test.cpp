// White furnace per BSDF lobe (nodes/bsdf.inc, runtime/shaders/common/bsdf_lobes.glsl): a
// sphere of one lobe, or of a Mix/Add Shader of lobes, under a uniform white sky. A pixel of
// the sphere is the BSDF's directional albedo at its view angle (the sphere is convex: every
// reflected ray sees the sky). Lossless lobes (Lambert, a smooth Glossy, mixes and sums of
// them with weights summing to 1) must give 1; lossy ones (Oren-Nayar, rough microfacets
// without multiple scattering, Velvet) at most 1 and above a stated floor. The transmission
// lobes send paths through the sphere and out again: Transparent, Translucent and a smooth
// Refraction need 3 rays (the hit, the far wall, the sky), Glass more (its internal
// reflections). In both architectures: the megakernel and the wavefront. A second test pins
// what --bounces does to a glass sphere (docs/guide/cli.md, "Bounces: what --bounces allows").
#include <gtest/gtest.h>

#include <array>
#include <ostream>
#include <string>
#include <tuple>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

struct FurnaceCase {
  const char* name;
  const char* graph;            // the lines after `material <name>;`
  std::array<double, 3> lower;  // the sphere's mean per channel must lie in [lower, upper]
  std::array<double, 3> upper;
  unsigned raysPerPath = 3;
};

// Lossless: 1 within 0.01 (a Lambert or mirror lobe's path weight is 1 or G1 ~ 1 on every
// path, so the estimate has almost no variance). Lossy lobes: at most 1, and above a floor
// under the analytic albedo near normal incidence (the middle pixels see the sphere nearly
// head-on); the means measured at 64 paths a pixel over 64 pixels (both architectures draw
// the same numbers) are in the comments.
const FurnaceCase kCases[] = {
    {"DiffuseLambert", "DiffuseBsdf Color=(1, 1, 1);\n", {0.99, 0.99, 0.99}, {1.01, 1.01, 1.01}},
    // Cycles' Oren-Nayar at normal view: t = 0, so the albedo is pi A = pi / (pi + (3 pi - 4)
    // / 6) = 0.7766 at sigma 1 (measured 0.7767).
    {"DiffuseOrenNayar",
     "DiffuseBsdf Color=(1, 1, 1) Roughness=1;\n",
     {0.75, 0.75, 0.75},
     {0.80, 0.80, 0.80}},
    {"GlossyGgxSmooth",
     "GlossyBsdf Color=(1, 1, 1) Roughness=0;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01}},
    // Single-scatter GGX at alpha 1 seen head-on: D = 1/pi, G1(i) = 2 cos / (1 + cos), so the
    // albedo is 1 - ln 2 = 0.307 (measured 0.2978; multiple scattering is what it lacks).
    {"GlossyGgxRough",
     "GlossyBsdf Color=(1, 1, 1) Roughness=1;\n",
     {0.27, 0.27, 0.27},
     {0.33, 0.33, 0.33}},
    {"GlossyBeckmannSmooth",
     "GlossyBsdf Color=(1, 1, 1) Roughness=0 Distribution=1;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01}},
    // Beckmann at alpha 0.64 loses less to single scattering (measured 0.8054).
    {"GlossyBeckmannRough",
     "GlossyBsdf Color=(1, 1, 1) Roughness=0.8 Distribution=1;\n",
     {0.7, 0.7, 0.7},
     {0.9, 0.9, 0.9}},
    // Ashikhmin's velvet is far from energy-conserving by design (measured 0.2223).
    {"Velvet", "VelvetBsdf Color=(1, 1, 1) Sigma=1;\n", {0.15, 0.15, 0.15}, {1.01, 1.01, 1.01}},
    {"MixDiffuseGlossy",
     "MixShader Fac=0.3 WeightA>0 WeightB>1;\n"
     "DiffuseBsdf Color=(1, 1, 1) Weight<0;\n"
     "GlossyBsdf Color=(1, 1, 1) Roughness=0 Weight<1;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01}},
    // Mix weights per colour: red only from the first shader (weight 0.75), green only from
    // the second (0.25). Red comes only from the paths that sampled the diffuse lobe (pick
    // probability 0.47 by luminance), each bringing about 0.75 / 0.47: a standard error of
    // about 0.0125 over the 4096 paths (measured 0.7696, 0.2437), so 3 of them either side.
    {"MixWeightsPerShader",
     "MixShader Fac=0.25 WeightA>0 WeightB>1;\n"
     "DiffuseBsdf Color=(1, 0, 0) Weight<0;\n"
     "GlossyBsdf Color=(0, 1, 0) Roughness=0 Weight<1;\n",
     {0.71, 0.235, 0.0},
     {0.79, 0.265, 0.001}},
    {"AddTwoHalfDiffuse",
     "DiffuseBsdf Color=(0.5, 0.5, 0.5);\n"
     "DiffuseBsdf Color=(0.5, 0.5, 0.5) Roughness=0;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01}},
    // Transmission lobes. Transparent passes everything straight through (1 exactly); its tint
    // applies at each of the two crossings, so Color (1, 0.5, 0.25) gives (1, 0.25, 0.0625).
    {"TransparentWhite",
     "TransparentBsdf Color=(1, 1, 1);\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01}},
    {"TransparentTintTwice",
     "TransparentBsdf Color=(1, 0.5, 0.25);\n",
     {0.99, 0.245, 0.06},
     {1.01, 0.255, 0.065}},
    // Translucent: every path enters (Lambert on the far side) and leaves at the far wall;
    // the tessellated sphere's shading normals end a few grazing paths (measured 0.9939).
    {"Translucent", "TranslucentBsdf Color=(1, 1, 1);\n", {0.98, 0.98, 0.98}, {1.01, 1.01, 1.01}},
    // A smooth Refraction lobe transmits all light (no Fresnel); a sphere never totally
    // reflects a ray that entered it, so every path leaves after the far wall.
    {"RefractionSmooth",
     "RefractionBsdf Color=(1, 1, 1) Roughness=0 IOR=1.5;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01}},
    // Rough refraction loses the shadowing G1(i) of each crossing and the rays that a rough
    // microfacet totally reflects inside (measured 0.8952 at Roughness 0.5, 8 rays).
    {"RefractionRough",
     "RefractionBsdf Color=(1, 1, 1) Roughness=0.5 IOR=1.5;\n",
     {0.75, 0.75, 0.75},
     {1.01, 1.01, 1.01},
     8},
    // Smooth glass conserves energy: reflected or refracted by Fresnel at each crossing, and
    // totally reflected inside where Fresnel is 1; 16 rays leave < 1e-4 of the paths inside.
    {"GlassSmooth",
     "GlassBsdf Color=(1, 1, 1) Roughness=0 IOR=1.5;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01},
     16},
    // Rough glass loses G1 and the rough-microfacet internal reflections past 16 rays
    // (measured 0.9931).
    {"GlassRoughBeckmann",
     "GlassBsdf Color=(1, 1, 1) Roughness=0.5 IOR=1.5 Distribution=1;\n",
     {0.75, 0.75, 0.75},
     {1.01, 1.01, 1.01},
     16},
    // The Principled BSDF's transmission (PrincipledLayers, Transmission 1: its diffuse and
    // specular weigh 0): smooth, the sharp glass's Fresnel choice at every crossing, so all
    // light leaves (measured 1.0000); rough (Roughness 0.3 for the reflection, 1 - 0.7 x 0.8 =
    // 0.44 for the refraction), GGX's G1 and the microfacets' internal reflections past 16
    // rays are lost (measured 0.9343). Tinted: the reflection is white and each refraction
    // is tinted (Cycles' base_color x glass weight), so a path leaves either by the first
    // reflection, F = 0.04, or after two refractions, tinted twice: 0.04 + 0.96 t^2 = (1,
    // 0.28, 0.1) for t = (1, 0.5, 0.25) (measured (1.0000, 0.2837, 0.1046): the Fresnel
    // choices and the pixels off normal incidence make F nearer 0.045 there).
    {"PrincipledTransmissionSmooth",
     "PrincipledOutput BaseColor=(1, 1, 1) Roughness=0 CyclesPrincipled=1;\n"
     "PrincipledLayers BaseColor=(1, 1, 1) Roughness=0 Transmission=1 IOR=1.5;\n",
     {0.99, 0.99, 0.99},
     {1.01, 1.01, 1.01},
     16},
    {"PrincipledTransmissionRough",
     "PrincipledOutput BaseColor=(1, 1, 1) Roughness=0.3 CyclesPrincipled=1;\n"
     "PrincipledLayers BaseColor=(1, 1, 1) Roughness=0.3 Transmission=1 "
     "TransmissionRoughness=0.2 IOR=1.5;\n",
     {0.75, 0.75, 0.75},
     {1.01, 1.01, 1.01},
     16},
    {"PrincipledTransmissionTinted",
     "PrincipledOutput BaseColor=(1, 0.5, 0.25) Roughness=0 CyclesPrincipled=1;\n"
     "PrincipledLayers BaseColor=(1, 0.5, 0.25) Roughness=0 Transmission=1 IOR=1.5;\n",
     {0.99, 0.27, 0.09},
     {1.01, 0.29, 0.11},
     16},
};

// gtest prints a case by its name, not its bytes.
void PrintTo(const FurnaceCase& c, std::ostream* os) {
  *os << c.name;
}

class BsdfLobeFurnace : public ::testing::TestWithParam<std::tuple<FurnaceCase, Shading>> {};

TEST_P(BsdfLobeFurnace, SphereUnderWhiteSkyReflectsItsAlbedo) {
  const auto& [c, shading] = GetParam();
  Scene scene;
  scene.meshes.push_back(testing::sphere(32));
  scene.materials.push_back({"Lobes", "", std::string("material Lobes;\n") + c.graph});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.environment.constantRadiance = glm::vec3(1.0f);
  scene.camera.position = {0, 0, 3};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 45.0f;

  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory.clear();  // the embedded library: nodes/bsdf.inc's sinks
  options.shading = shading;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = c.raysPerPath;
  settings.frames = 16;
  RenderResult result = renderer.render(scene, settings);

  for (int channel = 0; channel < 3; ++channel) {
    double mean = testing::meanChannel(result.image, channel, 12, 12, 20, 20);
    std::printf("furnace %s (%s) channel %d: %.4f\n", c.name, shadingName(shading), channel, mean);
    EXPECT_GE(mean, c.lower[channel]) << c.name << " channel " << channel;
    EXPECT_LE(mean, c.upper[channel]) << c.name << " channel " << channel;
  }
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

// --bounces is the rays of a path (the camera ray's hit is the first): a smooth glass sphere
// seen head-on needs 3 for the light through it (docs/guide/cli.md, "Bounces: what
// --bounces allows"). Closed
// forms at normal incidence, IOR 1.5 (F = ((1.5 - 1) / (1.5 + 1))^2 = 0.04): 1 ray gives 0
// (the sphere's hit, no continuation under a sky of no lights), 2 the reflection F = 0.04,
// 3 adds the path straight through, (1 - F)^2 = 0.9216 (0.9616), 4 the internal reflection
// that leaves by the near side after one more crossing, F (1 - F)^2 = 0.0369 (0.9985). The middle
// pixels see the sphere within 20 degrees of normal incidence, where F stays within 0.001
// of 0.04; each path is a Fresnel choice between exact ones, so the noise is a Bernoulli
// mean's, 0.003 over the 4096 paths at F = 0.04 (measured 0, 0.0449, 0.9578, 0.9976 in both
// architectures): within 0.01.
class GlassBounces : public ::testing::TestWithParam<Shading> {};

TEST_P(GlassBounces, GlassSphereBrightnessIsWhatTheBouncesAllow) {
  Shading shading = GetParam();
  const double expected[] = {0.0, 0.04, 0.9616, 0.9985};
  for (unsigned rays = 1; rays <= 4; ++rays) {
    Scene scene;
    scene.meshes.push_back(testing::sphere(32));
    scene.materials.push_back(
        {"Glass", "", "material Glass;\nGlassBsdf Color=(1, 1, 1) Roughness=0 IOR=1.5;\n"});
    scene.instances.push_back({0, 0, glm::mat4(1.0f)});
    scene.environment.constantRadiance = glm::vec3(1.0f);
    scene.camera.position = {0, 0, 3};
    scene.camera.target = {0, 0, 0};
    scene.camera.verticalFovDegrees = 45.0f;
    RendererOptions options = testing::testOptions();
    options.nodeLibraryDirectory.clear();
    options.shading = shading;
    Renderer renderer(options);
    RenderSettings settings;
    settings.width = settings.height = 32;
    settings.pathsPerPixel = 4;
    settings.raysPerPath = rays;
    settings.frames = 16;
    RenderResult result = renderer.render(scene, settings);
    double mean = testing::meanChannel(result.image, 1, 12, 12, 20, 20);
    std::printf("glass sphere (%s), %u rays a path: %.4f (closed form %.4f)\n",
                shadingName(shading), rays, mean, expected[rays - 1]);
    EXPECT_NEAR(mean, expected[rays - 1], 0.01) << rays << " rays a path";
    EXPECT_TRUE(renderer.context().validationErrors().empty());
  }
}

// Per-lobe normals (a BSDF node's Normal; docs/design/closures.md): a flat quad (normal +y)
// seen straight down, half a white Diffuse whose Normal is tilted 60 degrees towards +x and
// half a white mirror (Glossy, Roughness 0) about the material's normal. Under a white sky the
// mirror reflects the sky (1) and the Diffuse lobe, cosine-distributed about its tilted
// normal, sees the sky above the quad's plane alone: the cosine-weighted share of a
// hemisphere tilted by theta that lies above a plane is (1 + cos theta) / 2 = 0.75, so the
// mix gives 0.5 x 0.75 + 0.5 = 0.875 (1 where the Diffuse took the material's normal; 0.375
// where the mirror took the Diffuse's). Each path brings 1 or 0 (a Bernoulli mean of p
// 0.875): 0.005 standard error over the 4096 paths, so 0.02 either side. Under one sun of
// irradiance pi along -y and a black sky, only the Diffuse lobe sees the sun (the mirror is
// singular): 0.5 x (1 / pi) x cos 60 x pi = 0.25 exactly (0.5 about the material's normal).
class LobeNormals : public ::testing::TestWithParam<Shading> {};

const char* const kTiltedDiffuseAndMirror =
    "material Lobes;\n"
    "MixShader Fac=0.5 WeightA>0 WeightB>1;\n"
    "DiffuseBsdf Color=(1, 1, 1) Weight<0 Normal=(0.8660254, 0.5, 0);\n"
    "GlossyBsdf Color=(1, 1, 1) Roughness=0 Weight<1;\n";

// The quad (normal +y) under a white sky or one sun straight down, seen from straight above.
RenderResult renderLobeQuad(const char* graph, Shading shading, bool sky, unsigned frames = 16) {
  Scene scene;
  scene.meshes.push_back(testing::quad(4.0f));
  scene.materials.push_back({"Lobes", "", graph});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  if (sky) {
    scene.environment.constantRadiance = glm::vec3(1.0f);
  } else {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.intensity = glm::vec3(3.14159265f);
    scene.lights.push_back(sun);
  }
  scene.camera.position = {0, 3, 0};
  scene.camera.target = {0, 0, 0};
  scene.camera.up = {0, 0, -1};
  scene.camera.verticalFovDegrees = 30.0f;
  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory.clear();
  options.shading = shading;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 3;
  settings.frames = frames;
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  return result;
}

// The green mean of the quad's middle (8x8 pixels), where the tests read it.
double middleOfQuad(const RenderResult& result) {
  return testing::meanChannel(result.image, 1, 12, 12, 20, 20);
}

TEST_P(LobeNormals, TiltedDiffuseUnderWhiteSkySeesOnlyTheSkyAboveThePlane) {
  Shading shading = GetParam();
  RenderResult result = renderLobeQuad(kTiltedDiffuseAndMirror, shading, true);
  double mean = middleOfQuad(result);
  std::printf("tilted Diffuse + mirror under a white sky (%s): %.4f (closed form 0.875)\n",
              shadingName(shading), mean);
  EXPECT_NEAR(mean, 0.875, 0.02);
}

TEST_P(LobeNormals, TiltedDiffuseUnderOneSunFollowsItsOwnCosine) {
  Shading shading = GetParam();
  RenderResult result = renderLobeQuad(kTiltedDiffuseAndMirror, shading, false);
  double mean = middleOfQuad(result);
  std::printf("tilted Diffuse + mirror under one sun (%s): %.4f (closed form 0.25)\n",
              shadingName(shading), mean);
  EXPECT_NEAR(mean, 0.25, 0.005);
}

// PrincipledBsdf's Normal (a Principled BSDF under a Mix or Add Shader keeps its own normal):
// a white Principled base (Specular 0: its diffuse alone) whose Normal is tilted 60 degrees
// under the sun straight above is lit as one whose material normal (NormalOutput) is tilted
// so: the same lobe in the same frame, so the same value up to rounding. Light sampling alone
// lights the quad (a black sky, and bounces leave the flat quad for the sky): no noise. About
// the quad's own normal the diffuse sees the sun at cos 0 instead of cos 60, so it is far
// brighter.
TEST_P(LobeNormals, PrincipledBsdfIsShadedAboutItsOwnNormal) {
  Shading shading = GetParam();
  auto lit = [&](const char* graph) {
    RenderResult result = renderLobeQuad(graph, shading, false, 4);
    return middleOfQuad(result);
  };
  const char* principled = "PrincipledBsdf BaseColor=(1, 1, 1) Specular=0 Roughness=0.5";
  double own = lit(
      (std::string("material Lobes;\n") + principled + " Normal=(0.8660254, 0.5, 0);\n").c_str());
  double material = lit(
      (std::string("material Lobes;\nNormalOutput In=(0.8660254, 0.5, 0);\n") + principled + ";\n")
          .c_str());
  double upright = lit((std::string("material Lobes;\n") + principled + ";\n").c_str());
  std::printf(
      "PrincipledBsdf under one sun (%s): %.5f about its Normal, %.5f about the "
      "material's tilted normal, %.5f upright\n",
      shadingName(shading), own, material, upright);
  EXPECT_GT(upright, 0.1);
  EXPECT_NEAR(own, material, 1e-3 * material);
  EXPECT_LT(own, 0.75 * upright);
}

// The Principled BSDF's Clearcoat Normal: a black base (Specular 0) under a sharp clearcoat
// (Clearcoat Roughness 0.05), the sun and the camera straight above, so the coat shows the
// sun's highlight where its normal is the quad's (+y). Given explicitly as (0, 1, 0) it is
// the same highlight as with none (the octahedral code of +y is exact); tilted 30 degrees the
// half vector lies 30 degrees off the coat's normal, where GTR1 of alpha 0.0025 is 2.5e-5 of
// its peak (D 0.1 against 4251): the highlight goes, but for GTR1's long tail (measured 0.0012
// of the upright mean, whose pixels see the peak's neighbourhood), while with the coat about
// the material's normal it would stay. Light sampling alone lights the quad (a black sky):
// four frames suffice. The megakernel only: the lobes' code is the wavefront's too, whose
// per-lobe normals the Diffuse cases above check.
std::string clearcoatGraph(const char* clearcoatNormal) {
  return std::string(
             "material Lobes;\n"
             "PrincipledOutput BaseColor=(0, 0, 0) Specular=0 Roughness=0.5 CyclesPrincipled=1;\n"
             "PrincipledLayers BaseColor=(0, 0, 0) Roughness=0.5 Clearcoat=1 "
             "ClearcoatRoughness=0.05") +
         clearcoatNormal + ";\n";
}

TEST(LobeNormalsMegakernel, ClearcoatHighlightFollowsTheClearcoatNormal) {
  Shading shading = Shading::Megakernel;
  auto highlight = [&](const char* clearcoatNormal) {
    RenderResult result =
        renderLobeQuad(clearcoatGraph(clearcoatNormal).c_str(), shading, false, 4);
    return middleOfQuad(result);
  };
  double none = highlight("");
  double upright = highlight(" ClearcoatNormal=(0, 1, 0)");
  double tilted = highlight(" ClearcoatNormal=(0.5, 0.8660254, 0)");
  std::printf(
      "clearcoat highlight (%s): %.4f without ClearcoatNormal, %.4f upright, %.6f "
      "tilted 30 degrees\n",
      shadingName(shading), none, upright, tilted);
  EXPECT_GT(none, 0.1);
  EXPECT_NEAR(upright, none, 1e-4 * none);
  EXPECT_LT(tilted, 0.01 * none);
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, LobeNormals,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

INSTANTIATE_TEST_SUITE_P(BothArchitectures, GlassBounces,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

INSTANTIATE_TEST_SUITE_P(EveryLobeBothArchitectures, BsdfLobeFurnace,
                         ::testing::Combine(::testing::ValuesIn(kCases),
                                            ::testing::Values(Shading::Megakernel,
                                                              Shading::Wavefront)),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param).name) + "_" +
                                  shadingName(std::get<1>(info.param));
                         });

}  // namespace
}  // namespace memograph::runtime
