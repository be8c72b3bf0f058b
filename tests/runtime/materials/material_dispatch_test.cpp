// Material dispatch: on the ray-tracing pipeline, one callable shader per material must
// render exactly what the switch in the one path-tracer shader renders, textures included
// (each callable samples from its own first texture slot); callables on the query backend
// are refused with a message.
#include <chrono>
#include <cstring>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

std::string texturedGraph(const std::string& name, const std::string& texture) {
  return "material " + name + ";\nUVInput UV>0;\nImageTexture Image=\"" + texture +
         "\" UV<0 Color>1;\nBaseColorOutput Color<1;\nRoughnessOutput Roughness=0.6;\n";
}

// Six scene materials, five distinct graphs (one graph twice: one callable, two SBT
// records), two of them textured with different textures (texture bases 0 and 1).
Scene manyMaterialScene() {
  Scene scene;
  scene.meshes.push_back(testing::quad(10.0f, 4.0f));
  scene.meshes.push_back(testing::sphere(16));
  scene.materials.push_back({"Floor", "", texturedGraph("Floor", "red.pfm")});
  scene.materials.push_back({"A", "", testing::constantGraph("A", {0.9f, 0.2f, 0.2f}, 0.2f)});
  scene.materials.push_back({"B", "", testing::constantGraph("B", {0.2f, 0.9f, 0.2f}, 0.9f)});
  scene.materials.push_back({"C", "", texturedGraph("C", "blue.pfm")});
  scene.materials.push_back({"D", "", testing::constantGraph("D", {0.8f, 0.8f, 0.8f}, 0.05f)});
  scene.materials.push_back({"A again", "", testing::constantGraph("A", {0.9f, 0.2f, 0.2f}, 0.2f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  for (std::uint32_t i = 1; i < 6; ++i)
    scene.instances.push_back(
        {1, i, glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f + 1.2f * float(i), 1.0f, 0.0f))});
  scene.lights.push_back({LightType::Point, {2, 4, 2}, {0, -1, 0}, glm::vec3(20.0f)});
  scene.environment.constantRadiance = {0.3f, 0.4f, 0.5f};
  scene.camera.position = {0, 3, 7};
  scene.camera.target = {0, 0.8f, 0};
  return scene;
}

RendererOptions dispatchOptions(Backend backend, MaterialDispatch dispatch) {
  RendererOptions options = testing::testOptions(backend);
  options.materialDispatch = dispatch;
  options.textureLoader = [](const std::string& path) {
    return testing::flatTexture(path == "red.pfm" ? glm::vec3(0.9f, 0.1f, 0.1f)
                                                  : glm::vec3(0.1f, 0.1f, 0.9f));
  };
  return options;
}

RenderSettings settings() {
  RenderSettings s;
  s.width = 32;
  s.height = 20;
  s.pathsPerPixel = 2;
  s.raysPerPath = 3;
  s.seed = 3;
  return s;
}

TEST(MaterialDispatch, PipelineCallablesRenderLikeTheSwitch) {
  Scene scene = manyMaterialScene();
  RenderResult viaSwitch, viaCallables;
  {
    Renderer renderer(dispatchOptions(Backend::RayTracingPipeline, MaterialDispatch::Switch));
    viaSwitch = renderer.render(scene, settings());
    EXPECT_EQ(viaSwitch.stats.materialDispatch, "switch");
    EXPECT_TRUE(renderer.context().validationErrors().empty());
  }
  {
    // Auto means callables on the pipeline backend.
    Renderer renderer(dispatchOptions(Backend::RayTracingPipeline, MaterialDispatch::Auto));
    viaCallables = renderer.render(scene, settings());
    EXPECT_EQ(viaCallables.stats.materialDispatch, "callable");
    for (const auto& error : renderer.context().validationErrors())
      ADD_FAILURE() << "validation: " << error;
  }
  ASSERT_EQ(viaSwitch.image.rgba.size(), viaCallables.image.rgba.size());
  double worst = 0;
  for (std::size_t i = 0; i < viaSwitch.image.rgba.size(); ++i)
    worst = std::max(worst, double(std::abs(viaSwitch.image.rgba[i] - viaCallables.image.rgba[i])));
  bool identical = std::memcmp(viaSwitch.image.rgba.data(), viaCallables.image.rgba.data(),
                               viaSwitch.image.rgba.size() * sizeof(float)) == 0;
  std::printf("switch vs callables: max abs difference %.3g, bitwise identical: %s\n", worst,
              identical ? "yes" : "no");
  EXPECT_TRUE(identical);
  EXPECT_EQ(viaSwitch.stats.totalRays(), viaCallables.stats.totalRays());
  // The textures reached the callables: the red floor is red, not the default grey.
  double red = testing::meanChannel(viaCallables.image, 0, 0, 17, 32, 20);
  double blue = testing::meanChannel(viaCallables.image, 2, 0, 17, 32, 20);
  EXPECT_GT(red, 1.5 * blue) << "floor red " << red << " blue " << blue;
}

TEST(MaterialDispatch, CallablesOnTheQueryBackendAreRefused) {
  Renderer renderer(dispatchOptions(Backend::RayQuery, MaterialDispatch::Callable));
  try {
    renderer.render(manyMaterialScene(), settings());
    ADD_FAILURE() << "rendered";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pipeline"), std::string::npos) << e.what();
  }
}

TEST(MaterialDispatch, ManyMaterialSwitchOnCpuFailsFastNamingThePipelineBackend) {
  Renderer renderer(dispatchOptions(Backend::RayQuery, MaterialDispatch::Auto));
  if (renderer.context().info().type != VK_PHYSICAL_DEVICE_TYPE_CPU)
    GTEST_SKIP() << "the limit applies to CPU devices (lavapipe) only";
  Scene scene = manyMaterialScene();
  for (int i = 0; i < 12; ++i) {
    std::string name = "Extra" + std::to_string(i);
    scene.materials.push_back({name, "", testing::constantGraph(name, {0.5f, 0.5f, 0.5f}, 0.5f)});
  }
  auto start = std::chrono::steady_clock::now();
  try {
    renderer.render(scene, settings());
    ADD_FAILURE() << "rendered";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("17 distinct materials"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--backend pipeline"), std::string::npos) << e.what();
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0) << "it must refuse before compiling";
}

TEST(MaterialDispatch, NamesParse) {
  EXPECT_EQ(parseMaterialDispatch("auto"), MaterialDispatch::Auto);
  EXPECT_EQ(parseMaterialDispatch("switch"), MaterialDispatch::Switch);
  EXPECT_EQ(parseMaterialDispatch("callable"), MaterialDispatch::Callable);
  EXPECT_THROW(parseMaterialDispatch("inline"), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime

namespace memograph::runtime {
namespace {

TEST(MaterialDispatch, DistinctGraphsCountSharedGraphsOnce) {
  Scene scene;
  scene.materials = {{"a", "", "RoughnessOutput In=0.5;"},
                     {"b", "", "RoughnessOutput In=0.5;"},
                     {"c", "", "RoughnessOutput In=0.25;"},
                     {"d", "graphs/wood.mgraph", ""},
                     {"e", "graphs/wood.mgraph", ""}};
  EXPECT_EQ(countDistinctMaterialGraphs(scene), 3u);
}

}  // namespace
}  // namespace memograph::runtime
