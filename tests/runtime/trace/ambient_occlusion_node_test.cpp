// The Ambient Occlusion node in a material (a traced input, docs/design/traced-inputs.md):
// the megakernel traces the node's rays from the hit before the graph runs, with the settings
// the compiler recorded (the wavefront's traced-inputs pass does the same, tested against the
// megakernel in wavefront_traced_inputs_test.cpp). Each probe material emits its AO (black base
// colour, one ray a path: the pixel is the node's value), checked against analytic answers on both
// trace backends: a plane under a sphere (1 - (r/d)^2 cos(theta), as the AO integrator's test),
// Only Local (the sphere is another instance: exactly 1), and Inside on a sphere (a cosine-weighted
// chord 2 cos(theta) of a unit sphere is shorter than D with probability (D/2)^2).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/materials/material_linker.h"

namespace memograph::runtime {
namespace {

// Emits the AO node's Out (white times AO) and reflects nothing.
std::string aoProbe(const std::string& name, const std::string& settings) {
  return "material " + name + ";\nAmbientOcclusion " + settings +
         " Out>1;\n"
         "EmissionOutput Color<1 Strength=1.0;\n"
         "BaseColorOutput In=(0.0, 0.0, 0.0);\n"
         "SpecularOutput In=0.0;\n";
}

// A constant material in the real library's sockets (testing::constantGraph writes the test
// library's).
std::string constantColor(const std::string& name, const std::string& color) {
  return "material " + name + ";\nBaseColorOutput In=" + color + ";\n";
}

constexpr float kSphereRadius = 0.5f;
constexpr float kSphereHeight = 1.0f;

// The AO integrator test's scene: a plane of `planeGraph` under a black sphere, seen from
// where no pixel sees the sphere.
Scene planeUnderSphere(const std::string& planeGraph) {
  Scene scene;
  scene.meshes.push_back(testing::quad(20.0f));
  scene.meshes.push_back(testing::sphere(96));
  scene.materials.push_back({"Plane", "", planeGraph});
  scene.materials.push_back({"Black", "", constantColor("Black", "(0.0, 0.0, 0.0)")});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  glm::mat4 sphere = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, kSphereHeight, 0.0f));
  scene.instances.push_back({1, 1, glm::scale(sphere, glm::vec3(kSphereRadius))});
  scene.camera.position = {0.0f, 2.0f, 6.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 3.0f;
  return scene;
}

// Where the ray through the centre of pixel (x, y) meets the plane y = 0.
glm::dvec3 planePointOfPixel(const Camera& camera, int x, int y, int size) {
  const glm::dvec3 position(camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(glm::radians(double(camera.verticalFovDegrees)) * 0.5);
  const double ndcX = (x + 0.5) / size * 2.0 - 1.0;
  const double ndcY = (y + 0.5) / size * 2.0 - 1.0;
  const glm::dvec3 d = glm::normalize(forward + ndcX * tanHalf * right - ndcY * tanHalf * up);
  return position + (-position.y / d.y) * d;
}

double analyticAmbientOcclusion(glm::dvec3 p) {
  const glm::dvec3 toCentre = glm::dvec3(0.0, kSphereHeight, 0.0) - p;
  const double d = glm::length(toCentre);
  return 1.0 - (kSphereRadius / d) * (kSphereRadius / d) * (toCentre.y / d);
}

RenderResult renderProbe(const Scene& scene, Backend backend, std::uint32_t paths,
                         std::uint32_t frames) {
  RendererOptions options = testing::testOptions(backend);
  options.nodeLibraryDirectory.clear();  // the real node library, which has AmbientOcclusion
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.pathsPerPixel = paths;
  settings.frames = frames;
  settings.raysPerPath = 1;  // the primary hit: its emission (no light is reflected)
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  EXPECT_EQ(result.stats.shading, "megakernel");
  return result;
}

class AmbientOcclusionNode : public ::testing::TestWithParam<Backend> {};

TEST_P(AmbientOcclusionNode, PlaneUnderSphereMatchesTheAnalyticFraction) {
  const Scene scene = planeUnderSphere(aoProbe("PlaneAo", "Distance=100.0 Samples=32"));
  const RenderResult result = renderProbe(scene, GetParam(), 8, 4);
  // 32 paths of 32 rays a pixel: a pixel's estimate spreads by sqrt(0.8 * 0.2 / 1024) =
  // 0.0125; 0.07 is 5.6 of those, and the image's mean (0.0004) with the tessellation's
  // bias (0.0002) stays within 0.005.
  double sumError = 0.0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const double expected = analyticAmbientOcclusion(planePointOfPixel(scene.camera, x, y, 32));
      EXPECT_NEAR(result.image.pixel(x, y)[1], expected, 0.07) << "pixel " << x << "," << y;
      sumError += result.image.pixel(x, y)[1] - expected;
    }
  }
  std::printf("AO node, plane under sphere: mean error %.5f\n", sumError / 1024.0);
  EXPECT_NEAR(sumError / 1024.0, 0.0, 0.005);
  // Each path: its primary ray and the node's 32 rays (no shadow ray finds a light).
  for (const FrameStats& frame : result.stats.frames)
    EXPECT_GE(frame.rays, 32u * 32u * 8u * (1u + 32u));
}

TEST_P(AmbientOcclusionNode, OnlyLocalIgnoresOtherObjects) {
  const Scene scene =
      planeUnderSphere(aoProbe("PlaneLocal", "Distance=100.0 Samples=16 OnlyLocal=1.0"));
  const RenderResult result = renderProbe(scene, GetParam(), 2, 1);
  // Rays through the sphere find nothing of the plane's own instance: 1 everywhere (without
  // Only Local the pixels are 0.75..0.84).
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      ASSERT_NEAR(result.image.pixel(x, y)[1], 1.0f, 1e-6) << "pixel " << x << "," << y;
}

TEST_P(AmbientOcclusionNode, InsideASphereSeesItsChords) {
  Scene scene;
  scene.meshes.push_back(testing::sphere(96));
  scene.materials.push_back(
      {"SphereInside", "", aoProbe("SphereInside", "Distance=1.0 Samples=32 Inside=1.0")});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.camera.position = {0.0f, 0.0f, 4.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 10.0f;  // the sphere's middle fills the image
  const RenderResult result = renderProbe(scene, GetParam(), 8, 4);
  // Unoccluded where the chord 2 cos(theta) reaches past D = 1: 1 - (D/2)^2 = 0.75 (the
  // 96-segment sphere's chords are shorter by up to 0.05 %).
  const double mean = testing::meanChannel(result.image, 1, 0, 0, 32, 32);
  std::printf("AO node, inside a sphere: mean %.5f (analytic 0.75)\n", mean);
  EXPECT_NEAR(mean, 0.75, 0.005);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      EXPECT_NEAR(result.image.pixel(x, y)[1], 0.75, 0.07) << "pixel " << x << "," << y;
}

INSTANTIATE_TEST_SUITE_P(BothBackends, AmbientOcclusionNode,
                         ::testing::Values(Backend::RayQuery, Backend::RayTracingPipeline),
                         [](const auto& info) {
                           return std::string(info.param == Backend::RayQuery ? "query"
                                                                              : "pipeline");
                         });

TEST(AmbientOcclusionNodeLinking, OnlyGraphsWithTheNodeTraceRays) {
  MaterialLinkOptions link;  // the embedded (real) node library
  const MaterialRef plain{"Plain", "", constantColor("Plain", "(1.0, 0.0, 0.0)")};
  const MaterialRef probe{"Probe", "", aoProbe("Probe", "Distance=0.5 Samples=4 Inside=1.0")};
  EXPECT_FALSE(linkMaterials({plain}, link).tracedInputs);
  const LinkedMaterials linked = linkMaterials({plain, probe}, link);
  ASSERT_TRUE(linked.tracedInputs);
  EXPECT_EQ(linked.materials[0].ambientOcclusionSamples, 0u);
  EXPECT_EQ(linked.materials[1].ambientOcclusionSamples, 4u);
  EXPECT_FLOAT_EQ(linked.materials[1].ambientOcclusionDistance, 0.5f);
  EXPECT_EQ(linked.materials[1].ambientOcclusionFlags, kAmbientOcclusionInside);
  // Both dispatches' materials.glsl carry the table the megakernel reads (the prelude is also
  // the wavefront's: its traced-inputs pass reads it, wavefront_traced_inputs_test.cpp).
  EXPECT_NE(linked.source.find("mg_materialAmbientOcclusion"), std::string::npos);
  EXPECT_NE(linked.preludeSource.find("mg_materialAmbientOcclusion"), std::string::npos);
}

}  // namespace
}  // namespace memograph::runtime
