// The SPIR-V disk cache: a second start with the same sources compiles nothing; a changed
// source (another material) misses.
#include <filesystem>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/shader_compiler.h"

namespace memograph::runtime {
namespace {

TEST(ShaderCache, SecondRunLoadsSpirvFromDisk) {
  auto directory = std::filesystem::temp_directory_path() / "memograph-cache-test";
  std::filesystem::remove_all(directory);
  RendererOptions options = testing::testOptions();
  options.shaderCacheDirectory = directory;
  Scene scene;
  scene.meshes.push_back(testing::quad(2.0f));
  scene.materials.push_back({"A", "", testing::constantGraph("A", {0.5f, 0.5f, 0.5f}, 0.5f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.camera.position = {0, 3, 1};
  RenderSettings settings;
  settings.width = settings.height = 8;

  Renderer renderer(options);
  RenderResult first = renderer.render(scene, settings);
  EXPECT_GT(first.stats.shadersCompiled, 0u);
  EXPECT_EQ(first.stats.shaderCacheHits, 0u);
  RenderResult second = renderer.render(scene, settings);
  EXPECT_EQ(second.stats.shadersCompiled, 0u);
  EXPECT_EQ(second.stats.shaderCacheHits, first.stats.shadersCompiled);
  std::printf("shader cache: first start compiled %u shaders in %.1f ms, second loaded %u\n",
              first.stats.shadersCompiled, first.stats.shaderCompileMilliseconds,
              second.stats.shaderCacheHits);

  scene.materials[0].graphText = testing::constantGraph("A", {0.9f, 0.5f, 0.5f}, 0.5f);
  RenderResult third = renderer.render(scene, settings);
  EXPECT_GT(third.stats.shadersCompiled, 0u);
  std::filesystem::remove_all(directory);
}

TEST(ShaderCache, EachCallableMaterialHasItsOwnEntry) {
  auto directory = std::filesystem::temp_directory_path() / "memograph-callable-cache-test";
  std::filesystem::remove_all(directory);
  RendererOptions options = testing::testOptions(Backend::RayTracingPipeline);
  options.materialDispatch = MaterialDispatch::Callable;
  options.shaderCacheDirectory = directory;
  Scene scene;
  scene.meshes.push_back(testing::quad(2.0f));
  for (const char* name : {"A", "B", "C"})
    scene.materials.push_back({name, "", testing::constantGraph(name, {0.5f, 0.5f, 0.5f}, 0.5f)});
  for (std::uint32_t i = 0; i < 3; ++i)
    scene.instances.push_back({0, i, glm::mat4(1.0f)});
  scene.camera.position = {0, 3, 1};
  RenderSettings settings;
  settings.width = settings.height = 8;

  Renderer renderer(options);
  RenderResult first = renderer.render(scene, settings);
  // Raygen, two misses, closest hit, three callables.
  EXPECT_EQ(first.stats.shadersCompiled, 7u);
  RenderResult second = renderer.render(scene, settings);
  EXPECT_EQ(second.stats.shadersCompiled, 0u);
  EXPECT_EQ(second.stats.shaderCacheHits, 7u);
  // Another graph for one material: only its callable is compiled again.
  scene.materials[1].graphText = testing::constantGraph("B", {0.9f, 0.5f, 0.5f}, 0.5f);
  RenderResult third = renderer.render(scene, settings);
  EXPECT_EQ(third.stats.shadersCompiled, 1u);
  EXPECT_EQ(third.stats.shaderCacheHits, 6u);
  std::printf(
      "callable cache: first start compiled %u, second loaded %u, one changed material "
      "compiled %u\n",
      first.stats.shadersCompiled, second.stats.shaderCacheHits, third.stats.shadersCompiled);
  std::filesystem::remove_all(directory);
}

TEST(ShaderCache, CompileErrorsNameTheFile) {
  ShaderCompiler compiler({{"bad.comp", "#version 460\nvoid main() { undefined_call(); }\n"}}, {});
  try {
    compiler.compile({"bad.comp", ShaderStage::Compute, {}});
    ADD_FAILURE() << "compiled";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.comp"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace memograph::runtime
