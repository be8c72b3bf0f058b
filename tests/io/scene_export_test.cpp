// glTF export: what importScene reads back is the scene that was written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "tools/io/scene_export.h"
#include "tools/io/scene_import.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;

// Exports `scene`, writes its graphs into a materials folder and imports it again.
runtime::Scene roundTrip(const runtime::Scene& scene, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("memograph_export_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "materials");
  for (const runtime::MaterialRef& m : scene.materials) {
    std::ofstream(dir / "materials" / (m.name + ".mgraph")) << m.graphText;
  }
  compiler::Diagnostics diagnostics;
  const std::string path = (dir / (name + ".gltf")).string();
  EXPECT_TRUE(exportSceneGltf(scene, path, diagnostics))
      << compiler::formatDiagnostics(diagnostics);
  auto back = importScene(path, (dir / "materials").string(), diagnostics);
  fs::remove_all(dir);
  EXPECT_TRUE(back.has_value()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_FALSE(diagnostics.hasErrors()) << compiler::formatDiagnostics(diagnostics);
  return back ? std::move(*back) : runtime::Scene{};
}

void expectSameScene(const runtime::Scene& a, const runtime::Scene& b) {
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (std::size_t i = 0; i < a.instances.size(); ++i) {
    const runtime::Instance& x = a.instances[i];
    const runtime::Instance& y = b.instances[i];
    EXPECT_EQ(a.materials[x.material].name, b.materials[y.material].name) << i;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        EXPECT_NEAR(x.objectToWorld[c][r], y.objectToWorld[c][r], 1e-5f) << i;
      }
    }
    const runtime::Mesh& mx = a.meshes[x.mesh];
    const runtime::Mesh& my = b.meshes[y.mesh];
    EXPECT_EQ(mx.indices.size(), my.indices.size()) << i;
    EXPECT_EQ(mx.uvs.empty(), my.uvs.empty()) << i;
  }
  EXPECT_NEAR(glm::distance(a.camera.position, b.camera.position), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::dot(glm::normalize(a.camera.target - a.camera.position),
                       glm::normalize(b.camera.target - b.camera.position)),
              1.0f, 1e-5f);
  EXPECT_NEAR(a.camera.verticalFovDegrees, b.camera.verticalFovDegrees, 1e-3f);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].type, b.lights[i].type);
    EXPECT_NEAR(glm::distance(a.lights[i].intensity, b.lights[i].intensity), 0.0f, 1e-4f);
    if (a.lights[i].type == runtime::LightType::Point) {
      EXPECT_NEAR(glm::distance(a.lights[i].position, b.lights[i].position), 0.0f, 1e-4f);
    } else {
      EXPECT_NEAR(glm::dot(a.lights[i].direction, b.lights[i].direction), 1.0f, 1e-5f);
    }
  }
}

TEST(SceneExport, ClassroomRoundTripsThroughGltf) {
  const runtime::Scene scene = runtime::makeBuiltinScene("classroom");
  expectSameScene(scene, roundTrip(scene, "classroom"));
}

TEST(SceneExport, LandscapeRoundTripsThroughGltf) {
  runtime::BuiltinSceneOptions options;
  options.terrainCells = 32;
  const runtime::Scene scene = runtime::makeBuiltinScene("landscape", options);
  expectSameScene(scene, roundTrip(scene, "landscape"));
}

TEST(SceneExport, UnwritablePathIsAnError) {
  compiler::Diagnostics diagnostics;
  EXPECT_FALSE(exportSceneGltf(runtime::makeBuiltinScene("classroom"),
                               "/nonexistent/dir/scene.gltf", diagnostics));
  EXPECT_TRUE(diagnostics.hasErrors());
}

}  // namespace
}  // namespace memograph::io

namespace memograph::io {
namespace {

// The bundled example scene finds a graph for every material in examples/graphs.
TEST(ExampleScene, ShowcaseImportsWithEveryMaterialFound) {
  const std::string examples = MEMOGRAPH_EXAMPLES_DIR;
  compiler::Diagnostics diagnostics;
  const auto scene =
      importScene(examples + "/scenes/showcase.gltf", examples + "/graphs", diagnostics);
  ASSERT_TRUE(scene.has_value()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_TRUE(diagnostics.all().empty()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(scene->materials.size(), 14u);
  EXPECT_EQ(scene->lights.size(), 2u);
  for (const runtime::MaterialRef& m : scene->materials) {
    EXPECT_TRUE(fs::is_regular_file(m.graphPath)) << m.name;
  }
}

}  // namespace
}  // namespace memograph::io
