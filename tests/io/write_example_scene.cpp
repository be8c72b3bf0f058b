// Writes examples/scenes/showcase.gltf: boxes and spheres on a floor in a corner of two
// walls, each with a material named after a graph in examples/graphs/, so
// `--materials examples/graphs` renders every example graph. Usage:
// `scenes_write_example_scene OUT.gltf`.
#include <iostream>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scene/builtin/mesh_builder.h"
#include "runtime/scene/builtin/scene_builder.h"
#include "tools/io/scene_export.h"

int main(int argc, char** argv) {
  using namespace memograph;
  using namespace memograph::runtime;
  if (argc < 2) {
    std::cerr << "usage: scenes_write_example_scene OUT.gltf\n";
    return 2;
  }
  SceneBuilder b;
  // Materials by graph file stem; the graph text itself stays in examples/graphs.
  const auto material = [&](const char* stem) {
    b.scene().materials.push_back(
        MaterialRef{stem, std::string("examples/graphs/") + stem + ".mgraph", {}});
    return static_cast<std::uint32_t>(b.scene().materials.size() - 1);
  };
  const auto at = [](glm::vec3 p, float yawDegrees = 0.0f) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), p), glm::radians(yawDegrees),
                       glm::vec3(0, 1, 0));
  };
  b.instance(b.addMesh(boxesMesh("floor", {{{-4, -0.1f, -4}, {4, 0, 4}}})),
             material("checker_floor"), at({}));
  b.instance(b.addMesh(boxesMesh("back_wall", {{{-4, 0, -4.2f}, {4, 3, -4}}})),
             material("brick_wall"), at({}));
  b.instance(b.addMesh(boxesMesh("side_wall", {{{-4.2f, 0, -4}, {-4, 3, 4}}})),
             material("ceramic_tiles"), at({}));
  const auto cube = b.addMesh(boxesMesh("cube", {{{-0.5f, 0, -0.5f}, {0.5f, 1, 0.5f}}}));
  const auto slab = b.addMesh(boxesMesh("slab", {{{-0.9f, 0, -0.3f}, {0.9f, 0.6f, 0.3f}}}));
  const auto pane = b.addMesh(boxesMesh("pane", {{{-0.6f, 0, -0.02f}, {0.6f, 1.6f, 0.02f}}}));
  Mesh sphereMesh;
  sphereMesh.name = "sphere";
  appendDeformedSphere(sphereMesh, {0, 0.5f, 0}, {0.5f, 0.5f, 0.5f}, 32, 64,
                       [](glm::vec3) { return 1.0f; });
  const auto sphere = b.addMesh(std::move(sphereMesh));

  b.instance(cube, material("wood"), at({-2.2f, 0, -1.5f}, 20));
  b.instance(cube, material("rusty_metal"), at({-0.8f, 0, -2.3f}, -10));
  b.instance(slab, material("voronoi_stones"), at({1.6f, 0, -2.6f}, 5));
  b.instance(cube, material("textured_checker"), at({2.6f, 0, -0.6f}, 35));
  b.instance(sphere, material("marble"), at({-1.6f, 0, 0.2f}));
  b.instance(sphere, material("car_paint"), at({-0.3f, 0, -0.6f}));
  b.instance(sphere, material("normal_mapped"), at({1.0f, 0, -0.2f}));
  b.instance(sphere, material("lava"), at({0.2f, 0, 1.0f}));
  b.instance(sphere, material("displaced_noise"), at({1.9f, 0, 1.2f}));
  b.instance(sphere, material("normals_as_color"), at({-2.6f, 0, 1.4f}));
  b.instance(pane, material("stained_glass"), at({-3.0f, 0, -3.2f}, 30));

  Scene& scene = b.scene();
  Light lamp;
  lamp.position = {1.5f, 2.6f, 1.5f};
  lamp.intensity = glm::vec3(6.0f, 5.5f, 5.0f);
  scene.lights.push_back(lamp);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
  sun.intensity = glm::vec3(1.5f, 1.45f, 1.35f);
  scene.lights.push_back(sun);
  scene.environment.constantRadiance = {0.3f, 0.35f, 0.45f};
  scene.camera.position = {3.2f, 2.0f, 4.6f};
  scene.camera.target = {-0.2f, 0.5f, -1.0f};
  scene.camera.verticalFovDegrees = 50.0f;

  compiler::Diagnostics diagnostics;
  if (!io::exportSceneGltf(scene, argv[1], diagnostics)) {
    std::cerr << compiler::formatDiagnostics(diagnostics);
    return 1;
  }
  std::cout << "wrote " << argv[1] << '\n';
  return 0;
}
