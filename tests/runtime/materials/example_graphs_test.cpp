// Every example graph (examples/graphs/*.mgraph, real node library, embedded) links into
// the path tracer and renders finite radiance without validation errors: the generated
// includes, the prelude and the tracer's mg_SampleTexture fit together.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

std::vector<std::filesystem::path> exampleGraphs() {
  std::vector<std::filesystem::path> graphs;
  for (const auto& entry : std::filesystem::directory_iterator(MEMOGRAPH_EXAMPLES_DIR))
    if (entry.path().extension() == ".mgraph")
      graphs.push_back(entry.path());
  std::sort(graphs.begin(), graphs.end());
  return graphs;
}

// Textures come from OpenImageIO in the CLI; here every texture is a small checker.
TextureImage checker(const std::string&) {
  HdrImage image{8, 8, {}};
  for (int i = 0; i < 64; ++i) {
    float v = ((i % 8) / 2 + (i / 8) / 2) % 2 ? 0.9f : 0.1f;
    image.rgba.insert(image.rgba.end(), {v, v, 1.0f, 1.0f});
  }
  return TextureImage{{image}};
}

TEST(ExampleGraphs, EveryExampleRendersFiniteRadiance) {
  auto graphs = exampleGraphs();
  ASSERT_GE(graphs.size(), 10u);
  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory.clear();  // the embedded, real node library
  std::vector<std::string> textures;
  options.textureLoader = [&](const std::string& path) {
    textures.push_back(path);
    return checker(path);
  };
  Renderer renderer(options);
  for (const auto& graph : graphs) {
    Scene scene;
    scene.meshes.push_back(testing::sphere(16));
    scene.materials.push_back({graph.stem().string(), graph.string(), ""});
    scene.instances.push_back({0, 0, glm::mat4(1.0f)});
    scene.lights.push_back({LightType::Point, {2, 3, 3}, {0, -1, 0}, glm::vec3(10.0f)});
    scene.environment.constantRadiance = glm::vec3(0.2f);
    scene.camera.position = {0, 0, 3};
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.raysPerPath = 2;
    RenderResult result = renderer.render(scene, settings);
    int finite = 0;
    for (float v : result.image.rgba)
      finite += std::isfinite(v) ? 1 : 0;
    EXPECT_EQ(finite, int(result.image.rgba.size())) << graph;
    std::printf("example %-22s centre %.3f %.3f %.3f\n", graph.filename().c_str(),
                result.image.pixel(8, 8)[0], result.image.pixel(8, 8)[1],
                result.image.pixel(8, 8)[2]);
  }
  for (const auto& path : textures)
    EXPECT_TRUE(std::filesystem::exists(path)) << "texture path resolved wrongly: " << path;
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
