// Alpha (runtime/shaders/trace/stochastic_opacity.glsl, transparent_shadow.glsl): a path passes
// a surface of opacity alpha with probability 1 - alpha, so a pixel is (1 - alpha) x what lies
// behind + alpha x the surface, as Cycles 3.4 mixes a Principled BSDF's Alpha; a shadow ray is
// tinted 1 - alpha there; a ray passes at most eight such surfaces (Cycles' Max Transparent
// Bounces) and the ninth is shaded. Checked against closed forms in both architectures (the
// megakernel with either material dispatch); and a scene whose opacities are all 1 links no
// alpha code and renders byte-identically to one that writes none.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/materials/material_linker.h"
#include "runtime/renderer.h"

namespace memograph::runtime {
namespace {

constexpr double kPi = 3.14159265358979;
constexpr double kAlpha = 0.3;
constexpr const char* kFloor = "material Floor;\nDiffuseBsdf Color=(0.8, 0.8, 0.8);\n";
constexpr const char* kLeaf =
    "material Leaf;\nDiffuseBsdf Color=(0.2, 0.8, 0.2);\nOpacityOutput In=0.3;\n";
constexpr const char* kLeafOpaque =
    "material Leaf;\nDiffuseBsdf Color=(0.2, 0.8, 0.2);\nOpacityOutput In=1.0;\n";
constexpr const char* kLeafWithoutOpacity = "material Leaf;\nDiffuseBsdf Color=(0.2, 0.8, 0.2);\n";

constexpr int kWidth = 64;
constexpr int kHeight = 32;
constexpr float kHalfSide = 0.6f;

// The four architectures and dispatches every render test here runs.
struct Variant {
  Shading shading;
  Backend backend;
  const char* name;
};
const Variant kVariants[] = {
    {Shading::Megakernel, Backend::RayQuery, "megakernel, switch"},
    {Shading::Megakernel, Backend::RayTracingPipeline, "megakernel, callables"},
    {Shading::Wavefront, Backend::RayQuery, "wavefront, ray queries"},
    {Shading::Wavefront, Backend::RayTracingPipeline, "wavefront, pipeline"}};

HdrImage renderWith(const Scene& scene, const Variant& v, std::uint32_t paths) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.raysPerPath = 1;  // the camera ray and the direct light: closed forms
  settings.pathsPerPixel = paths;
  RendererOptions o = testing::testOptions(v.backend);
  o.nodeLibraryDirectory.clear();  // the real node library, which has the BSDF nodes
  o.shading = v.shading;
  return Renderer(o).render(scene, settings).image;
}

// A camera ray through pixel (x, y)'s centre (setCamera's basis).
glm::dvec3 cameraRay(const Scene& scene, int x, int y) {
  const glm::dvec3 eye(scene.camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(scene.camera.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(scene.camera.verticalFovDegrees * 0.5 * kPi / 180.0);
  const double aspect = double(kWidth) / kHeight;
  const double nx = ((x + 0.5) / kWidth * 2 - 1) * tanHalf * aspect;
  const double ny = ((y + 0.5) / kHeight * 2 - 1) * tanHalf;
  return glm::normalize(forward + nx * right - ny * up);
}

// Where a point (px, pz) lies against the horizontal rectangle centred at (x, z) of half sides
// (hx, hz): 1 well inside (0.2 m to spare, more than a pixel's jitter), 0 well outside, -1 near
// its edge.
int insideRectangle(double px, double pz, double x, double z, double hx, double hz) {
  const double dx = std::abs(px - x), dz = std::abs(pz - z);
  if (dx < hx - 0.2 && dz < hz - 0.2)
    return 1;
  if (dx > hx + 0.2 || dz > hz + 0.2)
    return 0;
  return -1;
}
int insideSquare(double px, double pz, double x, double z) {
  return insideRectangle(px, pz, x, z, kHalfSide, kHalfSide);
}

// A 3 m x 1.2 m Leaf plane (long in x) one metre over a diffuse floor, under a sun coming down
// at 45 degrees towards +x; the camera above sees the floor beside the plane, the floor
// through it, and the plane's shadow (one metre along +x) both directly and through the plane.
constexpr double kLeafHalfX = 2.5 * kHalfSide;
Scene leafScene(const char* leaf) {
  Scene scene;
  scene.meshes.push_back(testing::quad(20.0f));
  scene.meshes.push_back(testing::quad(2.0f * kHalfSide));
  scene.materials = {{"Floor", "", kFloor}, {"Leaf", "", leaf}};
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.instances.push_back({1, 1,
                             glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)),
                                        glm::vec3(2.5f, 1.0f, 1.0f))});
  scene.lights.push_back({LightType::Directional, glm::vec3(0.0f),
                          glm::normalize(glm::vec3(1, -1, 0)), glm::vec3(2.0f)});
  scene.camera.position = {0.0f, 6.0f, 0.5f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 30.0f;
  return scene;
}

// The mean of each class of pixel (the floor seen directly or through the plane, lit or in its
// shadow) against its closed form, with f cos E = albedo / pi x cos 45 degrees x 2 for the lit
// floor and the lit plane: through the plane (1 - alpha) x floor + alpha x plane, in its shadow
// the floor x (1 - alpha). The class means of 64 paths over >= 10 pixels each have a standard
// error below 0.5 % of the lit floor; the bound is 2 % of it. Opaque, the plane would make the
// through-the-plane classes its own colour, 2.5 times the bound away at least.
TEST(StochasticOpacity, PathsAndShadowsSeeThroughAPlaneOfOpacityPointThree) {
  const Scene scene = leafScene(kLeaf);
  const double cosE = std::sqrt(0.5) * 2.0;
  const glm::dvec3 floorLit = glm::dvec3(0.8) / kPi * cosE;
  const glm::dvec3 leafLit = glm::dvec3(0.2, 0.8, 0.2) / kPi * cosE;
  const glm::dvec3 planeCentre(0.0, 1.0, 0.0);
  for (const Variant& v : kVariants) {
    const HdrImage image = renderWith(scene, v, 64);
    glm::dvec3 sum[4] = {}, want[4] = {};
    int count[4] = {};
    const glm::dvec3 eye(scene.camera.position);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const glm::dvec3 d = cameraRay(scene, x, y);
        if (d.y >= 0.0)
          continue;
        const glm::dvec3 atPlane = eye + (planeCentre.y - eye.y) / d.y * d;
        const glm::dvec3 atFloor = eye - eye.y / d.y * d;
        const int through = insideRectangle(atPlane.x, atPlane.z, planeCentre.x, planeCentre.z,
                                            kLeafHalfX, kHalfSide);
        // Towards the sun from the floor point: up one metre, back one metre in x.
        const int shadowed = insideRectangle(atFloor.x - 1.0, atFloor.z, planeCentre.x,
                                             planeCentre.z, kLeafHalfX, kHalfSide);
        if (through < 0 || shadowed < 0 || std::abs(atFloor.x) > 9 || std::abs(atFloor.z) > 9)
          continue;
        const int c = through * 2 + shadowed;
        const glm::dvec3 floor = floorLit * (shadowed ? 1.0 - kAlpha : 1.0);
        want[c] = through ? (1.0 - kAlpha) * floor + kAlpha * leafLit : floor;
        const float* p = image.pixel(x, y);
        sum[c] += glm::dvec3(p[0], p[1], p[2]);
        ++count[c];
      }
    const char* names[4] = {"floor lit", "floor in the shadow", "through, lit", "through, shadow"};
    for (int c = 0; c < 4; ++c) {
      ASSERT_GE(count[c], 10) << v.name << ": " << names[c];
      const glm::dvec3 mean = sum[c] / double(count[c]);
      std::printf("%s: %s (%d pixels) %.4f %.4f %.4f, closed form %.4f %.4f %.4f\n", v.name,
                  names[c], count[c], mean.r, mean.g, mean.b, want[c].r, want[c].g, want[c].b);
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(mean[ch], want[c][ch], 0.02 * floorLit.r)
            << v.name << ": " << names[c] << " channel " << ch;
    }
  }
}

// Stacks of eight and nine emitting planes of opacity 0.1 over a black floor, no light: a ray
// passes at most eight (Cycles' Max Transparent Bounces 8), so the ninth plane, reached with
// probability 0.9^8, is shaded: through nine planes the pixel is sum_k 0.9^k 0.1 + 0.9^8 = 1,
// through eight 1 - 0.9^8 = 0.570 (the floor behind them is black). Without the limit nine would
// give 1 - 0.9^9 = 0.613. None of the crossings uses up the single ray of each path. Class
// means of 64 paths over >= 20 pixels: standard error about 0.015; the bound is 0.05.
TEST(StochasticOpacity, ARayPassesEightSurfacesAndTheNinthIsShaded) {
  constexpr const char* kGlow =
      "material Glow;\nDiffuseBsdf Color=(0, 0, 0);\nEmissionOutput Color=(1, 1, 1) "
      "Strength=1;\nOpacityOutput In=0.1;\n";
  constexpr const char* kBlack = "material Black;\nDiffuseBsdf Color=(0, 0, 0);\n";
  Scene scene;
  scene.meshes.push_back(testing::quad(20.0f));
  scene.meshes.push_back(testing::quad(2.0f * kHalfSide));
  scene.materials = {{"Black", "", kBlack}, {"Glow", "", kGlow}};
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  const double stackX[2] = {-0.8, 0.8};
  const int planes[2] = {8, 9};
  for (int s = 0; s < 2; ++s)
    for (int k = 0; k < planes[s]; ++k)
      scene.instances.push_back(
          {1, 1,
           glm::translate(glm::mat4(1.0f),
                          glm::vec3(float(stackX[s]), 1.0f + 0.03f * float(k), 0.0f))});
  scene.camera.position = {0.0f, 6.0f, 0.01f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 30.0f;
  const double want[2] = {1.0 - std::pow(0.9, 8), 1.0};
  // One variant of each architecture: the crossing loop is the same code in all four, which
  // the plane test above runs.
  for (const Variant& v : {kVariants[0], kVariants[3]}) {
    const HdrImage image = renderWith(scene, v, 64);
    double sum[2] = {};
    int count[2] = {};
    const glm::dvec3 eye(scene.camera.position);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const glm::dvec3 d = cameraRay(scene, x, y);
        if (d.y >= 0.0)
          continue;
        for (int s = 0; s < 2; ++s) {
          // Inside every plane of the stack (the lowest and the highest bound the rest).
          const glm::dvec3 low = eye + (1.0 - eye.y) / d.y * d;
          const glm::dvec3 high = eye + (1.0 + 0.03 * (planes[s] - 1) - eye.y) / d.y * d;
          if (insideSquare(low.x, low.z, stackX[s], 0.0) == 1 &&
              insideSquare(high.x, high.z, stackX[s], 0.0) == 1) {
            sum[s] += image.pixel(x, y)[1];
            ++count[s];
          }
        }
      }
    for (int s = 0; s < 2; ++s) {
      ASSERT_GE(count[s], 20) << v.name << ": stack of " << planes[s];
      const double mean = sum[s] / count[s];
      std::printf("%s: %d planes (%d pixels) %.4f, closed form %.4f\n", v.name, planes[s], count[s],
                  mean, want[s]);
      EXPECT_NEAR(mean, want[s], 0.05) << v.name << ": stack of " << planes[s];
    }
  }
}

// An emitting quad of opacity 0.5 over a diffuse floor, sampled as a light (NEE of emissive
// triangles, one ray a path so the floor's light is all light samples): each light sample takes
// 0.5 x the quad's emission, the expectation of a path's ray that finds it (Cycles weighs the
// expanded Principled's emission by Alpha). The same random numbers pick the same points as
// for the opaque quad, so every floor pixel is half the opaque render's, to rounding; in the
// megakernel and in the wavefront, whose light points' material pass applies the opacity.
TEST(StochasticOpacity, ALightSampleTakesOpacityTimesTheEmission) {
  auto glowScene = [](const char* glow) {
    Scene scene;
    scene.meshes.push_back(testing::quad(20.0f));
    scene.meshes.push_back(testing::quad(1.0f));
    scene.materials = {{"Floor", "", kFloor}, {"Glow", "", glow}};
    scene.materials[1].emissionEstimate = glm::vec3(4.0f);
    // Both graphs evaluated at the light samples (the linker would make the see-through one's
    // kind Graph anyway), so both renders take the same light-sampling code.
    scene.materials[1].emissionKind = MaterialRef::EmissionKind::Graph;
    scene.instances.push_back({0, 0, glm::mat4(1.0f)});
    scene.instances.push_back({1, 1, glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 1, 0))});
    scene.camera.position = {-3.0f, 3.0f, 0.0f};
    scene.camera.target = {0.0f, 0.0f, 0.0f};
    scene.camera.verticalFovDegrees = 40.0f;
    return scene;
  };
  const Scene half = glowScene(
      "material Glow;\nDiffuseBsdf Color=(0, 0, 0);\nEmissionOutput Color=(1, 1, 1) "
      "Strength=4;\nOpacityOutput In=0.5;\n");
  const Scene opaque = glowScene(
      "material Glow;\nDiffuseBsdf Color=(0, 0, 0);\nEmissionOutput Color=(1, 1, 1) "
      "Strength=4;\n");
  for (const Variant& v : {kVariants[0], kVariants[2]}) {
    const HdrImage a = renderWith(half, v, 4);
    const HdrImage b = renderWith(opaque, v, 4);
    int lit = 0;
    double worst = 0.0;
    const glm::dvec3 eye(half.camera.position);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        // The floor only: not where the camera ray may meet the quad (0.2 m to spare).
        const glm::dvec3 d = cameraRay(half, x, y);
        const glm::dvec3 atQuad = eye + (1.0 - eye.y) / d.y * d;
        if (d.y >= 0.0 || insideRectangle(atQuad.x, atQuad.z, 1.5, 0.0, 0.5, 0.5) != 0)
          continue;
        const float* p = a.pixel(x, y);
        const float* q = b.pixel(x, y);
        if (q[1] < 1e-3f)
          continue;
        ++lit;
        worst = std::max(worst, std::abs(double(p[1]) - 0.5 * q[1]) / q[1]);
      }
    std::printf("%s: %d lit floor pixels, largest |half - opaque / 2| / opaque %.2g\n", v.name, lit,
                worst);
    EXPECT_GE(lit, 100) << v.name;
    EXPECT_LT(worst, 1e-4) << v.name;
  }
}

// A graph whose opacity is 1 (a constant 1, or Principled's default Alpha) links no alpha code,
// and its scene renders byte-identically to the same scene whose graph writes no opacity.
TEST(StochasticOpacity, OpacityOneLinksNothingAndRendersAsWithout) {
  const LinkedMaterials opaque = linkMaterials({{"Floor", "", kFloor}, {"Leaf", "", kLeafOpaque}});
  EXPECT_FALSE(opaque.stochasticOpacity);
  EXPECT_FALSE(opaque.transparentShadows);
  EXPECT_EQ(opaque.source.find("materialStochasticOpacity"), std::string::npos);
  const LinkedMaterials principled = linkMaterials(
      {{"Floor", "", kFloor},
       {"Plain", "", "material Plain;\nPrincipledOutput BaseColor=(0.5, 0.5, 0.5);\n"},
       {"Alpha1", "", "material Alpha1;\nPrincipledOutput Alpha=1.0;\n"}});
  EXPECT_FALSE(principled.stochasticOpacity);
  const LinkedMaterials seeThrough = linkMaterials(
      {{"Floor", "", kFloor},
       {"Linked", "", "material Linked;\nFloat1Constant 0.5 Out>0;\nPrincipledOutput Alpha<0;\n"}});
  EXPECT_TRUE(seeThrough.stochasticOpacity);
  EXPECT_TRUE(seeThrough.transparentShadows);
  EXPECT_FALSE(seeThrough.materials[0].stochasticOpacity);
  EXPECT_TRUE(seeThrough.materials[1].stochasticOpacity);
  EXPECT_TRUE(seeThrough.materials[1].transparentShadow);
  EXPECT_NE(seeThrough.preludeSource.find("bool materialStochasticOpacity"), std::string::npos);

  for (const Variant& v : {kVariants[0], kVariants[2]}) {
    const HdrImage with = renderWith(leafScene(kLeafOpaque), v, 2);
    const HdrImage without = renderWith(leafScene(kLeafWithoutOpacity), v, 2);
    ASSERT_EQ(with.rgba.size(), without.rgba.size());
    EXPECT_EQ(0,
              std::memcmp(with.rgba.data(), without.rgba.data(), with.rgba.size() * sizeof(float)))
        << v.name;
  }
}

}  // namespace
}  // namespace memograph::runtime
