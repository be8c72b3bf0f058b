// The path tracer's object-space material inputs (docs/design/material-interface.md): Generated
// coordinates from the mesh's automatic texture space through the instance's inverse
// transform, Object Info (location, random), the geometric normal and backfacing. Two
// translated and scaled quads seen from above, each emitting what it reads.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/materials/material_linker.h"
#include "runtime/scene/scene_upload.h"

namespace memograph::runtime {
namespace {

namespace fs = std::filesystem;

// The test node library plus nodes that read the new inputs.
fs::path objectNodes() {
  const fs::path dir =
      fs::temp_directory_path() / ("memograph_object_inputs_nodes_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::copy(MEMOGRAPH_TEST_NODES_DIR, dir, fs::copy_options::recursive);
  std::ofstream(dir / "object.inc") << R"(
/// @input generated
void TestGenerated(in MaterialInputs inputs, out float3 Out) { Out = inputs.generated.v; }

/// @input objectPosition
void TestObject(in MaterialInputs inputs, out float3 Out) { Out = inputs.objectPosition.v; }

/// @input geometricNormal
/// @input objectLocation
/// @input objectRandom
/// @input backfacing
void TestInfo(in MaterialInputs inputs, out float3 Out) {
  Out = float3(inputs.backfacing + inputs.objectRandom, inputs.objectLocation.x,
               inputs.geometricNormal.y);
}

/// @input objectNormal
void TestObjectNormal(in MaterialInputs inputs, out float3 Out) {
  Out = inputs.objectNormal * 0.5 + 0.5;
}
)";
  return dir;
}

TEST(ObjectInputs, TextureSpaceIsBlendersAutomaticOne) {
  Mesh mesh = testing::quad(2.0f);  // x, z in [-1, 1], y = 0
  for (auto& p : mesh.positions)
    p += glm::vec3(1.0f, 0.0f, 0.5f);
  const TextureSpace space = autoTextureSpace(mesh);
  EXPECT_EQ(space.location, glm::vec3(1.0f, 0.0f, 0.5f));
  EXPECT_EQ(space.size, glm::vec3(1.0f, 1.0f, 1.0f));  // the flat y: 0 becomes 1
  mesh.positions = {{0, 0, 0}, {4, 1e-6f, 2}};
  EXPECT_EQ(autoTextureSpace(mesh).size, glm::vec3(2.0f, 1e-5f, 1.0f));
}

// The upload's texture spaces: a mesh's own (Blender's texture space, imported) replaces the
// automatic one, with a zero extent made 1 as Blender does.
TEST(ObjectInputs, AMeshsOwnTextureSpaceReplacesTheAutomaticOne) {
  Scene scene;
  scene.meshes = {testing::quad(2.0f), testing::quad(2.0f)};
  scene.meshes[1].hasTextureSpace = true;
  scene.meshes[1].textureSpaceLocation = glm::vec3(3.0f);
  scene.meshes[1].textureSpaceSize = glm::vec3(2.0f, 0.0f, 2.0f);
  const std::vector<TextureSpace> spaces = sceneTextureSpaces(scene);
  ASSERT_EQ(spaces.size(), 2u);
  EXPECT_EQ(spaces[0].location, glm::vec3(0.0f));
  EXPECT_EQ(spaces[0].size, glm::vec3(1.0f));
  EXPECT_EQ(spaces[1].location, glm::vec3(3.0f));
  EXPECT_EQ(spaces[1].size, glm::vec3(2.0f, 1.0f, 2.0f));  // a zero extent becomes 1
}

TEST(ObjectInputs, PathTracerFillsGeneratedObjectInfoAndFaceNormal) {
  const fs::path nodes = objectNodes();
  Scene scene;
  scene.meshes.push_back(testing::quad(2.0f));
  scene.materials.push_back({"Gen", "",
                             "material Gen;\nTestGenerated Out>0;\nEmissionOutput Color<0;\n"
                             "BaseColorOutput (0.0, 0.0, 0.0);\n"});
  scene.materials.push_back({"Info", "",
                             "material Info;\nTestInfo Out>0;\nEmissionOutput Color<0;\n"
                             "BaseColorOutput (0.0, 0.0, 0.0);\n"});
  const glm::mat4 scale2 = glm::mat4(glm::mat3(2.0f));
  glm::mat4 left = scale2, right = scale2;
  left[3] = glm::vec4(-3.0f, 0.0f, 0.0f, 1.0f);
  right[3] = glm::vec4(3.0f, 0.0f, 0.0f, 1.0f);
  scene.instances.push_back({0, 0, left});
  scene.instances.push_back({0, 1, right});
  scene.camera.position = {0.0f, 12.0f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};  // image x along world +x
  scene.camera.verticalFovDegrees = 60.0f;

  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory = nodes;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.raysPerPath = 1;
  settings.sharedPrimaryRay = true;
  const RenderResult result = renderer.render(scene, settings);
  fs::remove_all(nodes);

  // The ray through pixel centre (x, y) meets y = 0 at world (ndc.x, ., ndc.y) * 12 tan 30°.
  const float reach = 12.0f * std::tan(glm::radians(30.0f));
  const float random = float(pcgHash(1u ^ 0x5bd1e995u) >> 8) / 16777216.0f;
  int genPixels = 0, infoPixels = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const float wx = ((x + 0.5f) / 32 * 2 - 1) * reach;
      const float wz = ((y + 0.5f) / 32 * 2 - 1) * reach;
      const float* p = result.image.pixel(x, y);
      // Inside the left quad (x in [-5, -1]), away from its edges: Generated runs 0..1
      // over the object's box, 0.5 across its flat y.
      if (wx > -4.9f && wx < -1.1f && std::abs(wz) < 1.9f) {
        ++genPixels;
        EXPECT_NEAR(p[0], (wx + 5.0f) / 4.0f, 1e-3) << x << "," << y;
        EXPECT_NEAR(p[1], 0.5f, 1e-5) << x << "," << y;
        EXPECT_NEAR(p[2], (wz + 2.0f) / 4.0f, 1e-3) << x << "," << y;
      }
      if (wx > 1.1f && wx < 4.9f && std::abs(wz) < 1.9f) {
        ++infoPixels;
        EXPECT_NEAR(p[0], random, 1e-6) << x << "," << y;  // front face: backfacing 0
        EXPECT_NEAR(p[1], 3.0f, 1e-6) << x << "," << y;
        EXPECT_NEAR(p[2], 1.0f, 1e-5) << x << "," << y;  // the face normal, +y
      }
    }
  }
  EXPECT_GT(genPixels, 50);
  EXPECT_GT(infoPixels, 50);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

// The object-space normal (Texture Coordinate Normal, Box projection's weights) goes through
// the inverse of the instance's rotation and uneven scale, as Cycles'
// object_inverse_normal_transform: a quad whose object-space normal is +z, turned and
// stretched so that it faces the camera above (+y), reads +z, not the world's +y.
TEST(ObjectInputs, ObjectNormalUndoesTheInstancesRotationAndScale) {
  const fs::path nodes = objectNodes();
  Scene scene;
  Mesh mesh = testing::quad(2.0f);  // in y = 0, normal +y: turned to z = 0, normal +z
  const glm::mat3 toXy = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1, 0, 0}));
  for (auto& p : mesh.positions)
    p = toXy * p;
  for (auto& n : mesh.normals)
    n = toXy * n;
  ASSERT_NEAR(mesh.normals[0].z, 1.0f, 1e-6f);
  scene.meshes.push_back(mesh);
  scene.materials.push_back({"ObjectNormal", "",
                             "material ObjectNormal;\nTestObjectNormal Out>0;\n"
                             "EmissionOutput Color<0;\nBaseColorOutput (0.0, 0.0, 0.0);\n"});
  // Back to y = 0 facing +y, turned 30 degrees about y and stretched unevenly in the plane.
  glm::mat4 toWorld = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), {0, 1, 0}) *
                      glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), {1, 0, 0}) *
                      glm::scale(glm::mat4(1.0f), {3.0f, 1.5f, 0.5f});
  scene.instances.push_back({0, 0, toWorld});
  scene.camera.position = {0.0f, 12.0f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.verticalFovDegrees = 40.0f;

  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory = nodes;
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.raysPerPath = 1;
  settings.sharedPrimaryRay = true;
  const RenderResult result = renderer.render(scene, settings);
  fs::remove_all(nodes);

  const float* centre = result.image.pixel(8, 8);
  EXPECT_NEAR(centre[0], 0.5f, 1e-4);
  EXPECT_NEAR(centre[1], 0.5f, 1e-4);
  EXPECT_NEAR(centre[2], 1.0f, 1e-4);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

// The renderer compiles MaterialInputs without the object-space members
// (MG_OMIT_OBJECT_INPUTS) exactly when the linker says no graph reads one; a graph that
// reads any of them keeps them all.
TEST(ObjectInputs, LinkerSaysWhetherAnyGraphReadsObjectSpace) {
  const fs::path nodes = objectNodes();
  MaterialLinkOptions options;
  options.nodeLibraryDirectory = nodes;
  const MaterialRef plain{"Plain", "", "material Plain;\nBaseColorOutput (0.5, 0.5, 0.5);\n"};
  const MaterialRef generated{"Gen", "",
                              "material Gen;\nTestGenerated Out>0;\nEmissionOutput Color<0;\n"};
  const MaterialRef info{"Info", "", "material Info;\nTestInfo Out>0;\nEmissionOutput Color<0;\n"};
  const bool plainOnly = linkMaterials({plain}, options).objectInputs;
  const bool withGenerated = linkMaterials({plain, generated}, options).objectInputs;
  const bool withInfo = linkMaterials({info, plain}, options).objectInputs;
  fs::remove_all(nodes);
  EXPECT_FALSE(plainOnly);
  EXPECT_TRUE(withGenerated);
  EXPECT_TRUE(withInfo);
}

}  // namespace
}  // namespace memograph::runtime
