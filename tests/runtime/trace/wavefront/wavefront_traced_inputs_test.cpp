// Traced inputs in the wavefront (docs/design/traced-inputs.md): the Ambient Occlusion and
// Bevel nodes' rays are traced by the traced-inputs pass, between the hits' scatter and the
// material passes, from the hits of the materials that read them (the bin offsets pass puts
// their bins first), with the megakernel's estimators and random numbers. So at one seed the
// two architectures give the same picture, up to the compilers' rounding (1e-4 of a pixel's
// value, as Wavefront.AtOneSeedTheMegakernelTracesTheSamePaths states), and trace the same
// rays.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/renderer.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/wavefront/wavefront_passes.h"

namespace memograph::runtime {
namespace {

// A floor whose base colour is darkened by its Ambient Occlusion, a cube whose shading normal
// is its Bevel normal, and a sphere of a plain graph (a bin that reads no traced input, first
// in the scene's order, so the offsets pass must move it behind the other two), under a sun
// and a white sky: the traced inputs of camera and bounce hits both reach the picture.
Scene tracedInputsScene() {
  Scene scene;
  scene.meshes.push_back(testing::quad(6.0f));
  scene.meshes.push_back(testing::sphere(24));
  scene.meshes.push_back(testing::unitCube());
  scene.materials.push_back({"Plain", "",
                             "material Plain;\nBaseColorOutput In=(0.7, 0.3, 0.2);\n"
                             "RoughnessOutput In=0.6;\n"});
  scene.materials.push_back({"Occluded", "",
                             "material Occluded;\n"
                             "AmbientOcclusion Color=(0.8, 0.8, 0.8) Distance=1.0 Samples=4 "
                             "Out>1;\n"
                             "BaseColorOutput In<1;\nRoughnessOutput In=1.0;\n"});
  scene.materials.push_back({"Rounded", "",
                             "material Rounded;\n"
                             "Bevel Radius=0.2 Samples=4 Normal>1;\n"
                             "NormalOutput In<1;\n"
                             "BaseColorOutput In=(0.3, 0.5, 0.8);\nRoughnessOutput In=0.3;\n"});
  scene.instances.push_back({0, 1, glm::mat4(1.0f)});
  const glm::mat4 sphere = glm::translate(glm::mat4(1.0f), {0.8f, 0.5f, 0.0f});
  scene.instances.push_back({1, 0, glm::scale(sphere, glm::vec3(0.5f))});
  const glm::mat4 cube = glm::translate(glm::mat4(1.0f), {-0.7f, 0.5f, 0.2f});
  scene.instances.push_back({2, 2, glm::rotate(cube, 0.6f, glm::vec3(0, 1, 0))});
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.4f));
  sun.intensity = glm::vec3(2.0f);
  scene.lights.push_back(sun);
  scene.environment.constantRadiance = glm::vec3(0.5f);
  scene.camera.position = {0.0f, 2.0f, 3.5f};
  scene.camera.target = {0.0f, 0.3f, 0.0f};
  scene.camera.verticalFovDegrees = 40.0f;
  return scene;
}

// The scene above with what else adds path-state fields and passes around the traced
// inputs': the plain sphere's graph a Glossy BSDF lobe (the lobes' fields before the traced
// inputs'), and an emissive panel whose emission is its graph's (a checker over its
// position), so the light points' binning runs the offsets pass after the traced-inputs pass.
Scene tracedInputsWithLobesAndEmitterGraphs() {
  Scene scene = tracedInputsScene();
  scene.materials[0].graphText =
      "material Plain;\nGlossyBsdf Color=(0.7, 0.3, 0.2) Roughness=0.4;\n";
  scene.meshes.push_back(testing::quad(1.0f));
  MaterialRef panel;
  panel.name = "Panel";
  panel.graphText =
      "material Panel;\nPositionInput Out>0;\n"
      "CheckerTexture Vector<0 Color1=(6, 6, 6) Color2=(1, 2, 4) Scale=4 Color>1;\n"
      "EmissionOutput Color<1 Strength=1;\nBaseColorOutput In=(0, 0, 0);\n";
  panel.emissionEstimate = glm::vec3(4.0f);
  panel.emissionKind = MaterialRef::EmissionKind::Graph;
  scene.materials.push_back(panel);
  glm::mat4 place = glm::translate(glm::mat4(1.0f), {0.0f, 2.2f, 0.5f});
  place = glm::rotate(place, glm::radians(180.0f), glm::vec3(1, 0, 0));
  scene.instances.push_back({3, 3, place});
  return scene;
}

RenderResult renderTraced(const Scene& scene, Backend backend, Shading shading,
                          bool sharedPrimary) {
  RendererOptions options = testing::testOptions(backend);
  options.nodeLibraryDirectory.clear();  // the real node library, which has both nodes
  options.shading = shading;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.pathsPerPixel = 2;
  settings.raysPerPath = 3;  // the traced inputs of bounce hits too
  settings.frames = 1;
  settings.seed = 7;
  settings.sharedPrimaryRay = sharedPrimary;
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

// On both trace backends (the pass is a compute shader with ray queries, or a raygen of the
// wavefront's ray-tracing pipeline), and with --shared-primary (the camera hit's traced
// inputs are the pixel's first path's in both). Fails where the wavefront leaves a traced
// input at its default, traces from another hit, draws other numbers, or misses a bin.
TEST(WavefrontTracedInputs, AmbientOcclusionAndBevelGiveTheMegakernelsPictureAtOneSeed) {
  const Scene scene = tracedInputsScene();
  const struct {
    const char* name;
    Backend backend;
    bool sharedPrimary;
  } cases[] = {{"query", Backend::RayQuery, false},
               {"pipeline", Backend::RayTracingPipeline, false},
               {"query, shared primary ray", Backend::RayQuery, true}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const RenderResult megakernel =
        renderTraced(scene, c.backend, Shading::Megakernel, c.sharedPrimary);
    const RenderResult wavefront =
        renderTraced(scene, c.backend, Shading::Wavefront, c.sharedPrimary);
    const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
    const FrameStats& frame = wavefront.stats.frames.back();
    std::printf(
        "traced inputs, %s: largest relative difference %.3g, rays %llu (megakernel "
        "%llu)\n",
        c.name, difference, static_cast<unsigned long long>(frame.rays),
        static_cast<unsigned long long>(megakernel.stats.frames.back().rays));
    EXPECT_LT(difference, 1e-4);
    EXPECT_GT(testing::meanChannel(megakernel.image, 1, 0, 0, 16, 16), 0.01);
    // The same rays: the paths', and each traced input's (AO 4, Bevel up to 4 x 8 a hit).
    // With the shared primary ray the wavefront evaluates the camera hit's material every
    // round, so it traces that hit's traced inputs P times, the megakernel once.
    if (c.sharedPrimary) {
      EXPECT_GT(frame.rays, megakernel.stats.frames.back().rays);
    } else {
      EXPECT_EQ(frame.rays, megakernel.stats.frames.back().rays);
    }
    EXPECT_GT(frame.wavefrontTracedInputsMilliseconds, 0.0);  // timed as a pass of its own
    EXPECT_EQ(wavefront.stats.wavefrontMaterialPasses, 3u);
  }
}

// With BSDF lobes and an emitter's graph at light samples (their fields and passes beside the
// traced inputs': the lobes' fields come first, and the light points' binning runs the
// offsets pass again after the traced-inputs pass), the query backend's wavefront gives the
// megakernel's picture at one seed: measured 1.2e-7, bound 1e-4. Without a cache only: with
// the texel cache keying cuts (whose rest reads the traced input per hit) and with the tile
// cache it measured the same 1.2e-7, but their cold compiles on lavapipe took over a minute.
TEST(WavefrontTracedInputs, TheyComposeWithLobesAndEmitterGraphs) {
  const Scene scene = tracedInputsWithLobesAndEmitterGraphs();
  const RenderResult megakernel =
      renderTraced(scene, Backend::RayQuery, Shading::Megakernel, false);
  const RenderResult wavefront = renderTraced(scene, Backend::RayQuery, Shading::Wavefront, false);
  const double difference = largestRelativeDifference(megakernel.image, wavefront.image);
  std::printf("traced inputs with lobes and emitter graphs: largest relative difference %.3g\n",
              difference);
  EXPECT_LT(difference, 1e-4);
  EXPECT_EQ(wavefront.stats.frames.back().rays, megakernel.stats.frames.back().rays);
  EXPECT_EQ(wavefront.stats.wavefrontMaterialPasses, 4u);
}

// The pipelines a frame with traced inputs needs: the traced-inputs compute pass on the query
// backend, none more on the pipeline backend (its raygen joins the ray-tracing pipeline), and
// never without a material graph that reads a traced input.
TEST(WavefrontTracedInputs, TheirPassIsAComputePassOnlyOnTheQueryBackend) {
  WavefrontPipelineChoice choice;
  choice.materialPasses = 3;
  const std::uint32_t query = wavefrontPipelineCount(choice);
  choice.rayQuery = false;
  const std::uint32_t pipeline = wavefrontPipelineCount(choice);
  choice.tracedInputs = true;
  EXPECT_EQ(wavefrontPipelineCount(choice), pipeline);
  choice.rayQuery = true;
  EXPECT_EQ(wavefrontPipelineCount(choice), query + 1);
  const auto passes = wavefrontComputePasses(choice);
  EXPECT_NE(std::find(passes.begin(), passes.end(), gpu::kWavefrontTracedInputs), passes.end());
  // The AO integrator (no graphs): generate, trace, the AO pass in the traced-inputs pass's
  // slot and finish on the query backend; generate, finish and the ray-tracing pipeline (its
  // third raygen) on the pipeline backend.
  WavefrontPipelineChoice ambientOcclusion;
  ambientOcclusion.ambientOcclusionIntegrator = true;
  EXPECT_EQ(wavefrontComputePasses(ambientOcclusion),
            (std::vector<std::uint32_t>{gpu::kWavefrontGenerate, gpu::kWavefrontTrace,
                                        gpu::kWavefrontFinish, gpu::kWavefrontTracedInputs}));
  ambientOcclusion.rayQuery = false;
  EXPECT_EQ(wavefrontPipelineCount(ambientOcclusion), 3u);
  choice.materialPasses = 0;  // the floor: no graph reads anything
  const auto floorPasses = wavefrontComputePasses(choice);
  EXPECT_EQ(std::find(floorPasses.begin(), floorPasses.end(), gpu::kWavefrontTracedInputs),
            floorPasses.end());
}

}  // namespace
}  // namespace memograph::runtime
