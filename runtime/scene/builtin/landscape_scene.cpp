// The landscape built-in scene: a 400 m heightfield with one expensive terrain material,
// rocks and trees, a constant sky and a sun. It stands in for the thesis's Landscape scene
// (§6: an open exterior with few materials, one of them a complex terrain).
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/material_recipes.h"
#include "runtime/scene/builtin/procedural.h"
#include "runtime/scene/builtin/scene_builder.h"

namespace memograph::runtime {

float landscapeTerrainHeight(float x, float z) {
  // Rolling hills with a ridge towards +z and a shallow valley through the middle.
  const float hills = 28.0f * fbm(x / 160.0f, z / 160.0f, 7, 11u);
  const float ridge = 22.0f * glm::smoothstep(-50.0f, 180.0f, z);
  const float valley = -10.0f * std::exp(-(x * x) / (2 * 45.0f * 45.0f));
  return hills + ridge + valley;
}

Scene makeLandscapeScene(const BuiltinSceneOptions& options) {
  SceneBuilder b(options.onGeometry);
  const MaterialCost cost = options.materialCost;
  // Cheap objects keep their own detail low: the terrain is the one expensive material.
  // Half the octaves and no layers; the traced inputs as the others.
  const MaterialCost light{std::max(1, cost.octaves / 2), 0, cost.ambientOcclusionSamples,
                           cost.bevelSamples};
  const TerrainParams terrainParams{};
  const auto terrain =
      b.material("Landscape_Terrain", terrainGraph("Landscape_Terrain", terrainParams, cost));
  const auto rock =
      b.material("Landscape_Rock", rockGraph("Landscape_Rock", {}, RecipeSeed{101}, light));
  const auto bark =
      b.material("Landscape_Bark", barkGraph("Landscape_Bark", {}, RecipeSeed{102}, light));
  const auto leaves = b.material("Landscape_Foliage",
                                 foliageGraph("Landscape_Foliage", {}, RecipeSeed{103}, light));

  const float half = kLandscapeHalfSize;
  b.instance(b.addMesh(makeHeightfield("terrain", -half, -half, half, half, options.terrainCells,
                                       landscapeTerrainHeight, UvScale{terrainParams.metresPerUv})),
             terrain, glm::mat4(1.0f));

  // Three rock shapes, each a sphere displaced by its own noise.
  std::uint32_t rockMeshes[3];
  for (std::uint32_t i = 0; i < 3; ++i) {
    Mesh m;
    m.name = "rock_" + std::to_string(i);
    appendDeformedSphere(
        m, {0, 0, 0}, {1.6f + 0.4f * i, 1.0f + 0.2f * i, 1.3f}, 24, 48,
        [i](glm::vec3 d) {
          return 0.75f + 0.5f * valueNoise(d.x * 2.5f + d.y * 1.7f + 10.0f * i,
                                           d.z * 2.5f - d.y * 1.3f, 200 + i);
        },
        UvScale{1.0f});
    rockMeshes[i] = b.addMesh(std::move(m));
  }
  Mesh trunk;
  trunk.name = "tree_trunk";
  appendCylinder(trunk, {0, -0.5f, 0}, 0.35f, 5.5f, 16);
  const auto trunkMesh = b.addMesh(std::move(trunk));
  Mesh canopy;
  canopy.name = "tree_canopy";
  appendCone(canopy, {0, 3.0f, 0}, 2.6f, 7.0f, 24, UvScale{1.0f});
  appendCone(canopy, {0, 6.0f, 0}, 1.9f, 5.0f, 24, UvScale{1.0f});
  const auto canopyMesh = b.addMesh(std::move(canopy));

  // Scatter by a fixed hash so the layout is the same everywhere; objects sit on the
  // ground (sunk a little so they do not float on slopes).
  for (int i = 0; i < 24; ++i) {
    const float x = (hash2(i, 0, 7u) * 2 - 1) * half * 0.8f;
    const float z = (hash2(i, 1, 7u) * 2 - 1) * half * 0.8f;
    const float yaw = hash2(i, 2, 7u) * 6.2831853f;
    const float scale = 0.8f + 1.6f * hash2(i, 3, 7u);
    b.instance(rockMeshes[i % 3], rock,
               placed({x, landscapeTerrainHeight(x, z) - 0.3f * scale, z}, yaw, scale));
  }
  for (int i = 0; i < 40; ++i) {
    // Trees grow in two groves, so the fly-over passes both open ground and forest.
    const float cx = i % 2 ? 60.0f : -70.0f, cz = i % 2 ? -40.0f : 50.0f;
    const float x = cx + (hash2(i, 4, 9u) * 2 - 1) * 45.0f;
    const float z = cz + (hash2(i, 5, 9u) * 2 - 1) * 45.0f;
    const float yaw = hash2(i, 6, 9u) * 6.2831853f;
    const float scale = 0.8f + 0.5f * hash2(i, 7, 9u);
    const glm::mat4 m = placed({x, landscapeTerrainHeight(x, z), z}, yaw, scale);
    b.instance(trunkMesh, bark, m);
    b.instance(canopyMesh, leaves, m);
  }

  Scene& scene = b.scene();
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.45f, -0.75f, -0.35f));
  sun.intensity = glm::vec3(3.2f, 3.0f, 2.7f);
  scene.lights.push_back(sun);
  scene.environment.constantRadiance = glm::vec3(0.45f, 0.6f, 0.85f);
  const glm::vec3 eye{-150.0f, 0.0f, -150.0f};
  scene.camera.position = eye + glm::vec3(0, landscapeTerrainHeight(eye.x, eye.z) + 30.0f, 0);
  scene.camera.target = {0.0f, landscapeTerrainHeight(0, 0), 0.0f};
  scene.camera.verticalFovDegrees = 55.0f;
  scene.emissiveLightSampling = options.emissiveNee.value_or(true);  // it has no emitters yet
  return std::move(scene);
}

}  // namespace memograph::runtime
