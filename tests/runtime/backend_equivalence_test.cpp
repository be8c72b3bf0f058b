// One path-tracer source, two backends: the ray-query compute shader and the ray-tracing
// pipeline must give the same image for the same seed; and a seed fixes the image exactly.
#include <cstring>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

// A sphere on a floor, a point light and a sky: shadows, bounces, both lobes.
Scene testScene() {
  Scene scene;
  scene.meshes.push_back(testing::quad(10.0f, 4.0f));
  scene.meshes.push_back(testing::sphere(24));
  scene.materials.push_back(
      {"Floor", "", testing::constantGraph("Floor", {0.7f, 0.6f, 0.5f}, 0.8f)});
  scene.materials.push_back({"Ball", "", testing::constantGraph("Ball", {0.2f, 0.4f, 0.9f}, 0.3f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.instances.push_back({1, 1, glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0))});
  scene.lights.push_back({LightType::Point, {2, 4, 2}, {0, -1, 0}, glm::vec3(20.0f)});
  scene.lights.push_back(
      {LightType::Directional, {}, glm::normalize(glm::vec3(-1, -2, -1)), glm::vec3(0.5f)});
  scene.environment.constantRadiance = {0.3f, 0.4f, 0.5f};
  scene.camera.position = {0, 2, 5};
  scene.camera.target = {0, 0.8f, 0};
  return scene;
}

RenderSettings smallSettings(std::uint32_t seed) {
  RenderSettings settings;
  settings.width = 32;
  settings.height = 24;
  settings.pathsPerPixel = 2;
  settings.raysPerPath = 3;
  settings.frames = 2;
  settings.seed = seed;
  return settings;
}

TEST(BackendEquivalence, QueryAndPipelineGiveTheSameImage) {
  Scene scene = testScene();
  RenderResult query, pipeline;
  {
    Renderer renderer(testing::testOptions(Backend::RayQuery));
    query = renderer.render(scene, smallSettings(7));
    EXPECT_EQ(query.stats.backend, "query");
    EXPECT_TRUE(renderer.context().validationErrors().empty());
  }
  {
    Renderer renderer(testing::testOptions(Backend::RayTracingPipeline));
    pipeline = renderer.render(scene, smallSettings(7));
    EXPECT_EQ(pipeline.stats.backend, "pipeline");
    EXPECT_TRUE(renderer.context().validationErrors().empty());
  }
  ASSERT_EQ(query.image.rgba.size(), pipeline.image.rgba.size());
  double worst = 0;
  for (std::size_t i = 0; i < query.image.rgba.size(); ++i)
    worst = std::max(worst, double(std::abs(query.image.rgba[i] - pipeline.image.rgba[i])));
  bool identical = std::memcmp(query.image.rgba.data(), pipeline.image.rgba.data(),
                               query.image.rgba.size() * sizeof(float)) == 0;
  std::printf("backend equivalence: max abs difference %.3g, bitwise identical: %s\n", worst,
              identical ? "yes" : "no");
  // Same source, same RNG, same traversal: equal up to the two compilations' float rounding.
  EXPECT_LE(worst, 1e-4);
  EXPECT_EQ(query.stats.totalRays(), pipeline.stats.totalRays());
}

TEST(Determinism, SameSeedGivesIdenticalBytesAndOtherSeedsDiffer) {
  Scene scene = testScene();
  Renderer renderer(testing::testOptions());
  RenderResult a = renderer.render(scene, smallSettings(42));
  RenderResult b = renderer.render(scene, smallSettings(42));
  RenderResult c = renderer.render(scene, smallSettings(43));
  ASSERT_EQ(a.image.rgba.size(), b.image.rgba.size());
  EXPECT_EQ(
      std::memcmp(a.image.rgba.data(), b.image.rgba.data(), a.image.rgba.size() * sizeof(float)),
      0);
  EXPECT_NE(
      std::memcmp(a.image.rgba.data(), c.image.rgba.data(), a.image.rgba.size() * sizeof(float)),
      0);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

TEST(Stats, ReportsRaysTimesAndAccelerationStructureMemory) {
  Scene scene = testScene();
  // Five instances of two meshes: still two BLASes.
  for (int i = 0; i < 3; ++i)
    scene.instances.push_back(
        {1, 1, glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f + 3.0f * i, 0.5f, -2.0f))});
  Renderer renderer(testing::testOptions());
  RenderResult result = renderer.render(scene, smallSettings(1));
  const auto& as = result.stats.accelerationStructures;
  EXPECT_EQ(as.blasCount, 2u);
  EXPECT_EQ(as.instanceCount, 5u);
  EXPECT_GT(as.blasBytes, 0u);
  EXPECT_LE(as.blasBytes, as.blasBytesBeforeCompaction);
  EXPECT_GT(as.tlasBytes, 0u);
  EXPECT_GT(as.scratchBytes, 0u);
  ASSERT_EQ(result.stats.frames.size(), 2u);
  // At least one primary ray per path and pixel.
  EXPECT_GE(result.stats.frames[0].rays, 32u * 24u * 2u);
  std::printf(
      "stats: BLAS %llu B (uncompacted %llu B), TLAS %llu B, scratch %llu B, "
      "frame 0: %.3f ms GPU, %llu rays\n",
      (unsigned long long)as.blasBytes, (unsigned long long)as.blasBytesBeforeCompaction,
      (unsigned long long)as.tlasBytes, (unsigned long long)as.scratchBytes,
      result.stats.frames[0].gpuMilliseconds, (unsigned long long)result.stats.frames[0].rays);
}

}  // namespace
}  // namespace memograph::runtime
