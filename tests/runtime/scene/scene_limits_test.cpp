// The scene's fixed limits (scene_limits.h), measured from the Scene alone: what the validate
// stage refuses for every importer and built-in scene before the device sees it.
#include "runtime/scene/scene_limits.h"

#include <gtest/gtest.h>

namespace memograph::runtime {
namespace {

Mesh triangle() {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals.assign(3, {0, 0, 1});
  mesh.indices = {0, 1, 2};
  return mesh;
}

std::string refusal(const Scene& scene) {
  try {
    checkSceneLimits(measureScene(scene));
  } catch (const SceneLimitError& e) {
    return e.what();
  }
  return {};
}

TEST(SceneLimits, SceneWithMoreMeshesThanTheLimitIsRefusedNamingTheCount) {
  Scene scene;
  scene.materials.push_back({"m", {}, "material m;\n"});
  scene.meshes.assign(50000, triangle());
  for (std::uint32_t m = 0; m < 50000; ++m)
    scene.instances.push_back({m, 0});
  EXPECT_EQ(refusal(scene),
            "the scene has 50000 meshes, more than the limit of 16384 (each mesh is an "
            "acceleration structure of its own; an OBJ gets one mesh per material ('usemtl') "
            "of each object)");
}

TEST(SceneLimits, SceneWithMoreDistinctGraphsThanTheLimitIsRefused) {
  Scene scene;
  scene.meshes.push_back(triangle());
  scene.instances.push_back({0, 0});
  for (int m = 0; m < 5000; ++m) {
    const std::string name = std::string("m").append(std::to_string(m));
    scene.materials.push_back({name, {}, std::string("material ").append(name).append(";\n")});
  }
  const std::string message = refusal(scene);
  EXPECT_NE(message.find("5000 distinct material graphs, more than the limit of 4096"),
            std::string::npos)
      << message;
}

TEST(SceneLimits, ManyMaterialsSharingOneGraphAreOneGraph) {
  Scene scene;
  scene.meshes.push_back(triangle());
  scene.instances.push_back({0, 0});
  scene.materials.assign(10000, MaterialRef{"missing", {}, "material missing;\n"});
  const SceneFootprint f = measureScene(scene);
  EXPECT_EQ(f.materials, 10000u);
  EXPECT_EQ(f.materialGraphs, 1u);
  EXPECT_EQ(refusal(scene), "");
}

TEST(SceneLimits, FootprintCountsTheBuffersUploadSceneMakes) {
  Scene scene;
  scene.materials.push_back({"lamp", {}, "material lamp;\n", glm::vec3(1.0f)});
  scene.meshes.push_back(triangle());
  scene.instances.push_back({0, 0});
  scene.instances.push_back({0, 0});
  const SceneFootprint f = measureScene(scene);
  EXPECT_EQ(f.vertexBytes, 3 * sizeof(gpu::Vertex));
  EXPECT_EQ(f.indexBytes, 12u);
  EXPECT_EQ(f.instanceBytes, 2 * sizeof(gpu::Instance));
  EXPECT_EQ(f.lightBytesAtMost, 2 * sizeof(gpu::Light));  // one emissive triangle an instance
}

TEST(SceneLimits, TexturesPastTheirLimitsAreRefused) {
  EXPECT_NO_THROW(checkTextureLimits(kMaxSceneTextures, kMaxSceneTexels));
  EXPECT_THROW(checkTextureLimits(kMaxSceneTextures + 1, 0), SceneLimitError);
  EXPECT_THROW(checkTextureLimits(1, kMaxSceneTexels + 1), SceneLimitError);
}

TEST(SceneLimits, GeometryPastTheDeviceBufferRangeIsRefusedNamingTheLimit) {
  const SceneBufferBudget budget{"Tiny GPU", 64 * 16, 0};
  EXPECT_NO_THROW(checkGeometryBuffers(budget, 16, 1));
  try {
    checkGeometryBuffers(budget, 17, 1, true);
    ADD_FAILURE() << "17 vertices of 64 bytes passed a 1024-byte range";
  } catch (const SceneLimitError& e) {
    EXPECT_STREQ(e.what(),
                 "the scene's vertex buffer would need at least 1088 bytes (17 vertices of 64 "
                 "bytes so far), more than the 1024-byte storage-buffer range of Tiny GPU "
                 "(maxStorageBufferRange, the most one binding may address)");
  }
  const SceneBufferBudget allocation{"Tiny GPU", 0, 12};
  try {
    checkGeometryBuffers(allocation, 0, 2);
    ADD_FAILURE() << "24 bytes of indices passed a 12-byte allocation";
  } catch (const SceneLimitError& e) {
    EXPECT_STREQ(e.what(),
                 "the scene's index buffer would need 24 bytes (2 triangles of 12 bytes), more "
                 "than the largest allocation of Tiny GPU (12 bytes)");
  }
  EXPECT_NO_THROW(checkGeometryBuffers(SceneBufferBudget{}, 1u << 30, 1u << 30));
}

}  // namespace
}  // namespace memograph::runtime
