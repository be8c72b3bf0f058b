// Transparent shadows (runtime/shaders/trace/transparent_shadow.glsl): a shadow ray passes the
// surfaces of materials that write a Transparent lobe, tinted by the lobe's colour at each,
// and stops at any other surface or at the ninth transparent one (Cycles 3.4 at its default
// Max Transparent Bounces 8; the Blender scene transparent_shadows checks Cycles does so).
// Checked against closed forms on a lit floor, in both architectures (the megakernel with
// either material dispatch); and the linker gives the scenes without such a material no shadow code
// at all.
#include <cmath>
#include <cstdio>
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
constexpr const char* kFloor = "material Floor;\nDiffuseBsdf Color=(0.8, 0.8, 0.8);\n";
constexpr const char* kTinted = "material Tinted;\nTransparentBsdf Color=(0.9, 0.6, 0.3);\n";
constexpr const char* kOpaque = "material Opaque;\nDiffuseBsdf Color=(0.5, 0.5, 0.5);\n";
constexpr const char* kLayer = "material Layer;\nTransparentBsdf Color=(0.9, 0.8, 0.7);\n";
// Blender's "no shadow" trick: diffuse to every ray but shadow rays, which see a white
// Transparent BSDF (Is Shadow Ray is 1 at a shadow ray's hit).
constexpr const char* kNoShadow =
    "material NoShadow;\n"
    "LightPath IsShadowRay>0;\n"
    "MixShader Fac<0 WeightA>1 WeightB>2;\n"
    "DiffuseBsdf Color=(0.5, 0.5, 0.5) Weight<1;\n"
    "TransparentBsdf Color=(1, 1, 1) Weight<2;\n";

// Five stacks of 1.2 m square planes over a diffuse floor, left to right: one Tinted plane,
// one Opaque plane, eight Layer planes, nine Layer planes (3 cm apart from 1 m up), one
// NoShadow plane. The sun
// comes down at 45 degrees towards +z, so each stack's shadow lies beside it, where the camera
// above sees it without looking through a plane.
constexpr float kHalfSide = 0.6f;
constexpr int kStacks = 5;
constexpr float kStackX[kStacks] = {-3.0f, -1.5f, 0.0f, 1.5f, 3.0f};
constexpr int kStackPlanes[kStacks] = {1, 1, 8, 9, 1};
float planeHeight(int k) {
  return 1.0f + 0.03f * float(k);
}

Scene stacksScene() {
  Scene scene;
  scene.meshes.push_back(testing::quad(20.0f));
  scene.meshes.push_back(testing::quad(2.0f * kHalfSide));
  scene.materials = {{"Floor", "", kFloor},
                     {"Tinted", "", kTinted},
                     {"Opaque", "", kOpaque},
                     {"Layer", "", kLayer},
                     {"NoShadow", "", kNoShadow}};
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  const std::uint32_t stackMaterial[kStacks] = {1, 2, 3, 3, 4};
  for (int stack = 0; stack < kStacks; ++stack)
    for (int k = 0; k < kStackPlanes[stack]; ++k)
      scene.instances.push_back(
          {1, stackMaterial[stack],
           glm::translate(glm::mat4(1.0f), glm::vec3(kStackX[stack], planeHeight(k), 0.0f))});
  scene.lights.push_back({LightType::Directional, glm::vec3(0.0f),
                          glm::normalize(glm::vec3(0, -1, 1)), glm::vec3(2.0f)});
  scene.camera.position = {0.0f, 6.0f, 6.0f};
  scene.camera.target = {0.0f, 0.0f, 1.0f};
  scene.camera.verticalFovDegrees = 30.0f;
  return scene;
}

constexpr int kWidth = 64;
constexpr int kHeight = 32;

// What a pixel's camera ray (through its centre, setCamera's basis) finds: the floor point
// it hits (false where it crosses a plane first or misses the floor), and which stack's planes
// the sun's ray from that point crosses: -1 none, with 0.1 m to spare; -2 some but not all of
// one stack's, or too near an edge to tell.
bool floorPointOf(const Scene& scene, int x, int y, int& stack) {
  const glm::dvec3 eye(scene.camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(scene.camera.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(scene.camera.verticalFovDegrees * 0.5 * kPi / 180.0);
  const double aspect = double(kWidth) / kHeight;
  const double nx = ((x + 0.5) / kWidth * 2 - 1) * tanHalf * aspect;
  const double ny = ((y + 0.5) / kHeight * 2 - 1) * tanHalf;
  const glm::dvec3 d = glm::normalize(forward + nx * right - ny * up);
  if (d.y >= 0.0)
    return false;
  const double tFloor = -eye.y / d.y;
  for (int s = 0; s < kStacks; ++s)
    for (int k = 0; k < kStackPlanes[s]; ++k) {
      const double t = (planeHeight(k) - eye.y) / d.y;
      const glm::dvec3 p = eye + t * d;
      if (t > 0 && t < tFloor && std::abs(p.x - kStackX[s]) < kHalfSide + 0.05 &&
          std::abs(p.z) < kHalfSide + 0.05)
        return false;
    }
  const glm::dvec3 p = eye + tFloor * d;
  if (std::abs(p.x) > 9.0 || std::abs(p.z) > 9.0)
    return false;
  stack = -1;
  for (int s = 0; s < kStacks; ++s) {
    int inside = 0, near = 0;
    for (int k = 0; k < kStackPlanes[s]; ++k) {
      // Towards the sun: up one metre, back one metre in z.
      const double dx = std::abs(p.x - kStackX[s]);
      const double dz = std::abs(p.z - planeHeight(k));
      if (dx < kHalfSide - 0.1 && dz < kHalfSide - 0.1)
        ++inside;
      else if (dx < kHalfSide + 0.1 && dz < kHalfSide + 0.1)
        ++near;
    }
    if (inside == kStackPlanes[s] && near == 0)
      stack = s;
    else if (inside > 0 || near > 0)
      stack = -2;
    if (stack != -1)
      break;
  }
  return true;
}

// One ray a path (the floor's direct light alone) through each pixel's centre: a lit floor
// pixel is the diffuse floor's f cos E = 0.8 / pi x cos 45 degrees x 2, and a shadowed one
// that times what the stack lets through: the Tinted colour, 0 for the Opaque plane, the
// Layer colour to the 8th power, 0 for nine Layer planes (Cycles passes eight), and all of
// it for the NoShadow plane.
TEST(TransparentShadow, FloorUnderStacksGetsTheirTransmittance) {
  const Scene scene = stacksScene();
  const double lit = 0.8 / kPi * std::sqrt(0.5) * 2.0;
  const glm::dvec3 layer(0.9, 0.8, 0.7);
  const glm::dvec3 eight = layer * layer * layer * layer * layer * layer * layer * layer;
  const glm::dvec3 expected[kStacks] = {glm::dvec3(0.9, 0.6, 0.3), glm::dvec3(0.0), eight,
                                        glm::dvec3(0.0), glm::dvec3(1.0)};
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.raysPerPath = 1;
  settings.sharedPrimaryRay = true;
  // The megakernel on the query backend (the switch) and on the pipeline backend (material
  // callables), and the wavefront on both (its shadow pass a compute shader, or a raygen as
  // on the GPU).
  for (const auto& [shading, backend] :
       {std::pair{Shading::Megakernel, Backend::RayQuery},
        std::pair{Shading::Megakernel, Backend::RayTracingPipeline},
        std::pair{Shading::Wavefront, Backend::RayQuery},
        std::pair{Shading::Wavefront, Backend::RayTracingPipeline}}) {
    const bool query = backend == Backend::RayQuery;
    const char* name = shading == Shading::Wavefront
                           ? (query ? "wavefront, ray queries" : "wavefront, pipeline")
                           : (query ? "megakernel, switch" : "megakernel, callables");
    RendererOptions o = testing::testOptions(backend);
    o.nodeLibraryDirectory.clear();  // the real node library, which has the BSDF nodes
    o.shading = shading;
    const HdrImage image = Renderer(o).render(scene, settings).image;
    int counted[kStacks + 1] = {};  // per stack, then the lit floor
    double worst = 0.0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        int stack = -1;
        if (!floorPointOf(scene, x, y, stack) || stack == -2)
          continue;
        const glm::dvec3 want = lit * (stack < 0 ? glm::dvec3(1.0) : expected[stack]);
        const float* p = image.pixel(x, y);
        for (int ch = 0; ch < 3; ++ch) {
          const double error = std::abs(p[ch] - want[ch]);
          worst = std::max(worst, error / lit);
          EXPECT_NEAR(p[ch], want[ch], 1e-3 * lit)
              << name << ": pixel " << x << "," << y << " channel " << ch << " stack " << stack;
        }
        ++counted[stack < 0 ? kStacks : stack];
      }
    std::printf(
        "%s: pixels per stack %d %d %d %d %d, lit %d; largest error %.2g of the lit value\n", name,
        counted[0], counted[1], counted[2], counted[3], counted[4], counted[5], worst);
    for (int n : counted)
      EXPECT_GE(n, 4) << name;  // every case is seen
  }
}

// Only a graph that calls TransparentBsdf (here under a Mix Shader) is evaluated at shadow
// hits; a scene without one links no shadow code, so its shaders stay as they were.
TEST(TransparentShadow, OnlyGraphsWithATransparentLobeAreEvaluatedAtShadowHits) {
  const LinkedMaterials opaque = linkMaterials({{"Floor", "", kFloor}, {"Opaque", "", kOpaque}});
  EXPECT_FALSE(opaque.transparentShadows);
  EXPECT_TRUE(opaque.shadowSource.empty());
  EXPECT_EQ(opaque.source.find("materialTransparentShadow"), std::string::npos);
  EXPECT_EQ(opaque.preludeSource.find("materialTransparentShadow"), std::string::npos);

  constexpr const char* kMixed =
      "material Mixed;\n"
      "MixShader Fac=0.5 WeightA>0 WeightB>1;\n"
      "DiffuseBsdf Color=(1, 1, 1) Weight<0;\n"
      "TransparentBsdf Color=(1, 1, 1) Weight<1;\n";
  const LinkedMaterials mixed = linkMaterials({{"Floor", "", kFloor}, {"Mixed", "", kMixed}});
  ASSERT_EQ(mixed.materials.size(), 2u);
  EXPECT_TRUE(mixed.transparentShadows);
  EXPECT_FALSE(mixed.materials[0].transparentShadow);
  EXPECT_TRUE(mixed.materials[1].transparentShadow);
  // The shadow pass's switch holds the Mixed graph alone.
  EXPECT_NE(mixed.shadowSource.find("EvaluateMaterial_Mixed("), std::string::npos);
  EXPECT_EQ(mixed.shadowSource.find("EvaluateMaterial_Floor("), std::string::npos);
  EXPECT_NE(mixed.preludeSource.find("bool materialTransparentShadow"), std::string::npos);
}

}  // namespace
}  // namespace memograph::runtime
