// validateScene: built-in scenes pass; each broken invariant is reported by name.
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/mesh_builder.h"
#include "runtime/scene/builtin/scene_validation.h"

namespace memograph::runtime {
namespace {

Scene oneBox() {
  Scene scene;
  Mesh mesh;
  mesh.name = "box";
  appendBox(mesh, {0, 0, 0}, {1, 1, 1});
  computeTangents(mesh);
  scene.meshes.push_back(mesh);
  scene.materials.push_back({"M", "", "material M;\n"});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  return scene;
}

std::string errorsOf(const Scene& scene) {
  compiler::Diagnostics diagnostics;
  validateScene(scene, "test.gltf", diagnostics);
  return compiler::formatDiagnostics(diagnostics);
}

TEST(SceneValidation, BuiltinScenesAreValid) {
  BuiltinSceneOptions options;
  options.terrainCells = 16;
  options.cityScale = 0.02;  // the full city has its own test (city_scene_test.cpp)
  for (const std::string& name : builtinSceneNames()) {
    compiler::Diagnostics diagnostics;
    EXPECT_TRUE(validateScene(makeBuiltinScene(name, options), name, diagnostics))
        << compiler::formatDiagnostics(diagnostics);
  }
  EXPECT_EQ(errorsOf(oneBox()), "");
}

TEST(SceneValidation, EachBrokenInvariantIsNamed) {
  Scene s = oneBox();
  s.meshes[0].indices.push_back(99);
  EXPECT_NE(errorsOf(s).find("mesh 0 ('box') has 37 indices, not a multiple of 3"),
            std::string::npos);
  EXPECT_NE(errorsOf(s).find("index 36 is 99, but the mesh has 24 vertices"), std::string::npos);

  s = oneBox();
  s.meshes[0].normals.pop_back();
  EXPECT_NE(errorsOf(s).find("has 23 normals for 24 vertices"), std::string::npos);

  s = oneBox();
  s.meshes[0].positions[3].x = NAN;
  EXPECT_NE(errorsOf(s).find("vertex 3 is not finite"), std::string::npos);

  s = oneBox();
  s.instances[0].material = 4;
  EXPECT_NE(errorsOf(s).find("instance 0 uses material 4, but there are 1"), std::string::npos);

  s = oneBox();
  s.materials[0].graphPath = "m.mgraph";
  EXPECT_NE(errorsOf(s).find("exactly one of a graph file and graph text"), std::string::npos);

  s = oneBox();
  s.camera.target = s.camera.position;
  EXPECT_NE(errorsOf(s).find("camera has no view direction"), std::string::npos);

  s = oneBox();
  s.lights.push_back({LightType::Directional, {}, glm::vec3(0.0f), glm::vec3(1.0f)});
  EXPECT_NE(errorsOf(s).find("light 0 is directional but has no direction"), std::string::npos);

  s = oneBox();
  s.instances.clear();
  EXPECT_EQ(errorsOf(s).rfind("test.gltf: error: the scene has no instances", 0), 0u);
}

}  // namespace
}  // namespace memograph::runtime
