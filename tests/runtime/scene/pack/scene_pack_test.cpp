// The scene pack's codec (runtime/scene/pack/): a round trip keeps every field and gives the
// same bytes again; truncated, corrupted, foreign and inconsistent packs are refused with a
// message naming the file and the offset, never a crash or a huge allocation.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "runtime/scene/pack/pack_bytes.h"
#include "runtime/scene/pack/scene_pack.h"

namespace memograph::runtime {
namespace {

ScenePack makePack() {
  ScenePack pack;
  Scene& scene = pack.scene;
  Mesh quad;
  quad.name = "quad";
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.tangents = {{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, -1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.hasTextureSpace = true;
  quad.textureSpaceLocation = {0.5f, 0.5f, 0.0f};
  quad.textureSpaceSize = {0.5f, 0.5f, 0.25f};
  Mesh triangle;
  triangle.name = "triangle";
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  triangle.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 0.5f}};
  triangle.indices = {0, 1, 2};
  scene.meshes = {quad, triangle};
  scene.materials = {{.name = "floor", .graphText = "UVInput Out>0;\nBaseColorOutput In<0;\n"},
                     {.name = "lamp",
                      .graphText = "EmissionOutput (2.0, 2.0, 2.0);\n",
                      .emissionEstimate = {2, 2, 2},
                      .emissionKind = MaterialRef::EmissionKind::ConstantFront}};
  scene.instances = {
      {.mesh = 0, .material = 0},
      {.mesh = 1, .material = 1, .objectToWorld = glm::mat4(2.0f), .castsShadow = false}};
  scene.lights = {{.type = LightType::Point, .position = {1, 2, 3}, .intensity = {4, 5, 6}},
                  {.type = LightType::Spot,
                   .position = {0, 3, 0},
                   .spotCosHalfAngle = 0.8f,
                   .spotSmooth = 0.05f},
                  {.type = LightType::Directional, .direction = {0, -1, 0}}};
  scene.camera = {.position = {0, 1, 4}, .target = {0, 0.5f, 0}, .verticalFovDegrees = 50};
  scene.environment.constantRadiance = {0.1f, 0.2f, 0.3f};
  scene.environment.imagePath = "sky.exr";
  scene.environment.imageWidth = 2;
  scene.environment.imageHeight = 1;
  scene.environment.imageRgb = {1, 2, 3, 4, 5, 6};
  scene.emissiveLightSampling = false;
  scene.filterGlossy = 0.75f;
  scene.animatedMeshes = {1};
  gpu::VertexMotion motion{};
  motion.drift = {0.1f, 0, 0, 0};
  scene.animatedMotions = {motion};
  pack.cameraPath = {scene.camera, {.position = {1, 1, 4}}};
  pack.textures = {
      {"textures/checker.png", {.width = 2, .height = 1, .rgba = {1, 0, 0, 1, 0, 1, 0, 1}}}};
  return pack;
}

bool sameCamera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.target == b.target && a.up == b.up &&
         a.verticalFovDegrees == b.verticalFovDegrees;
}

// The header's checksum recomputed, so a test can reach the decoder's later checks.
void resealPayload(std::string& bytes) {
  const std::uint64_t hash = pack::fnv1a64(std::string_view(bytes).substr(32));
  std::memcpy(bytes.data() + 24, &hash, sizeof hash);
}

TEST(ScenePack, ARoundTripKeepsEveryFieldAndGivesTheSameBytes) {
  const ScenePack original = makePack();
  const std::string bytes = encodeScenePack(original);
  std::string error;
  const auto decoded = decodeScenePack(bytes, "s.mgpack", error);
  ASSERT_TRUE(decoded) << error;
  const Scene& a = original.scene;
  const Scene& b = decoded->scene;
  ASSERT_EQ(b.meshes.size(), 2u);
  for (std::size_t m = 0; m < 2; ++m) {
    EXPECT_EQ(b.meshes[m].name, a.meshes[m].name);
    EXPECT_EQ(b.meshes[m].positions, a.meshes[m].positions);
    EXPECT_EQ(b.meshes[m].normals, a.meshes[m].normals);
    EXPECT_EQ(b.meshes[m].uvs, a.meshes[m].uvs);
    EXPECT_EQ(b.meshes[m].tangents, a.meshes[m].tangents);
    EXPECT_EQ(b.meshes[m].colors, a.meshes[m].colors);
    EXPECT_EQ(b.meshes[m].indices, a.meshes[m].indices);
    EXPECT_EQ(b.meshes[m].hasTextureSpace, a.meshes[m].hasTextureSpace);
    EXPECT_EQ(b.meshes[m].textureSpaceSize, a.meshes[m].textureSpaceSize);
  }
  ASSERT_EQ(b.instances.size(), 2u);
  EXPECT_EQ(b.instances[1].mesh, 1u);
  EXPECT_EQ(b.instances[1].objectToWorld, glm::mat4(2.0f));
  EXPECT_FALSE(b.instances[1].castsShadow);
  ASSERT_EQ(b.materials.size(), 2u);
  EXPECT_EQ(b.materials[1].graphText, a.materials[1].graphText);
  EXPECT_TRUE(b.materials[1].graphPath.empty());
  EXPECT_EQ(b.materials[1].emissionKind, MaterialRef::EmissionKind::ConstantFront);
  EXPECT_EQ(b.materials[1].emissionEstimate, glm::vec3(2.0f));
  ASSERT_EQ(b.lights.size(), 3u);
  EXPECT_EQ(b.lights[1].type, LightType::Spot);
  EXPECT_EQ(b.lights[1].spotCosHalfAngle, 0.8f);
  EXPECT_EQ(b.lights[0].intensity, glm::vec3(4, 5, 6));
  EXPECT_TRUE(sameCamera(b.camera, a.camera));
  EXPECT_EQ(b.environment.imageRgb, a.environment.imageRgb);
  EXPECT_EQ(b.environment.imagePath, "sky.exr");
  EXPECT_EQ(b.environment.constantRadiance, a.environment.constantRadiance);
  EXPECT_FALSE(b.emissiveLightSampling);
  EXPECT_EQ(b.filterGlossy, 0.75f);  // a Blender scene's Filter Glossy travels to the GPU bundle
  EXPECT_EQ(b.animatedMeshes, a.animatedMeshes);
  ASSERT_EQ(b.animatedMotions.size(), 1u);
  EXPECT_EQ(b.animatedMotions[0].drift.x, 0.1f);
  ASSERT_EQ(decoded->cameraPath.size(), 2u);
  EXPECT_TRUE(sameCamera(decoded->cameraPath[1], original.cameraPath[1]));
  ASSERT_EQ(decoded->textures.size(), 1u);
  EXPECT_EQ(decoded->textures[0].name, "textures/checker.png");
  EXPECT_EQ(decoded->textures[0].image.rgba, original.textures[0].image.rgba);
  EXPECT_EQ(encodeScenePack(*decoded), bytes);
}

TEST(ScenePack, EveryTruncationIsRefusedWithTheFileAndOffset) {
  const std::string bytes = encodeScenePack(makePack());
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    std::string error;
    EXPECT_FALSE(decodeScenePack(std::string_view(bytes).substr(0, length), "s.mgpack", error))
        << length;
    EXPECT_EQ(error.rfind("s.mgpack: offset ", 0), 0u) << length << ": " << error;
  }
  std::string error;
  ASSERT_FALSE(
      decodeScenePack(std::string_view(bytes).substr(0, bytes.size() - 5), "s.mgpack", error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
}

TEST(ScenePack, AFlippedPayloadByteFailsTheChecksum) {
  std::string bytes = encodeScenePack(makePack());
  bytes[bytes.size() / 2] ^= 0x10;
  std::string error;
  EXPECT_FALSE(decodeScenePack(bytes, "s.mgpack", error));
  EXPECT_EQ(error, "s.mgpack: offset 32: corrupt: the payload's checksum does not match");
}

TEST(ScenePack, AnotherFileOrVersionIsNamed) {
  std::string error;
  EXPECT_FALSE(decodeScenePack("glTF and more bytes than a header has, surely", "a.mgpack", error));
  EXPECT_EQ(error, "a.mgpack: offset 0: not a memograph scene pack (no MGPACK magic)");
  std::string bytes = encodeScenePack(makePack());
  bytes[8] = 3;
  EXPECT_FALSE(decodeScenePack(bytes, "a.mgpack", error));
  EXPECT_NE(error.find("offset 8: format version 3; this memograph reads version 2"),
            std::string::npos)
      << error;
}

TEST(ScenePack, AHugeCountIsRefusedBeforeAnythingIsAllocated) {
  std::string bytes = encodeScenePack(makePack());
  const std::uint32_t huge = 0xffffffffu;
  std::memcpy(bytes.data() + 32, &huge, sizeof huge);  // the mesh count
  resealPayload(bytes);
  std::string error;
  EXPECT_FALSE(decodeScenePack(bytes, "s.mgpack", error));
  EXPECT_EQ(error, "s.mgpack: offset 32: meshes count 4294967295 runs past the end of the file");
}

TEST(ScenePack, ReferencesOutOfRangeAreRefused) {
  ScenePack pack = makePack();
  pack.scene.instances[1].mesh = 7;
  std::string error;
  EXPECT_FALSE(decodeScenePack(encodeScenePack(pack), "s.mgpack", error));
  EXPECT_NE(error.find("instance mesh 7 of 2 meshes"), std::string::npos) << error;
  pack = makePack();
  pack.scene.meshes[0].indices[4] = 9;
  EXPECT_FALSE(decodeScenePack(encodeScenePack(pack), "s.mgpack", error));
  EXPECT_NE(error.find("mesh 'quad' has index 9 past its 4 vertices"), std::string::npos) << error;
  pack = makePack();
  pack.scene.instances[0].material = 2;
  EXPECT_FALSE(decodeScenePack(encodeScenePack(pack), "s.mgpack", error));
  EXPECT_NE(error.find("instance 0 names material 2 of 2"), std::string::npos) << error;
}

TEST(ScenePack, AMaterialWithoutGraphTextIsNotWritten) {
  ScenePack pack = makePack();
  pack.scene.materials[0].graphText.clear();
  pack.scene.materials[0].graphPath = "floor.mgraph";
  const auto path = std::filesystem::temp_directory_path() / "scene_pack_test_no_text.mgpack";
  std::string error;
  EXPECT_FALSE(writeScenePack(path, pack, error));
  EXPECT_NE(error.find("material 'floor' has no graph text"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ScenePack, AFileRoundTripsAndAMissingOneIsNamed) {
  const auto path = std::filesystem::temp_directory_path() / "scene_pack_test.mgpack";
  std::string error;
  ASSERT_TRUE(writeScenePack(path, makePack(), error)) << error;
  const auto read = readScenePack(path, error);
  ASSERT_TRUE(read) << error;
  EXPECT_EQ(read->textures.size(), 1u);
  EXPECT_EQ(packedTexture(read->textures, "textures/checker.png").levels[0].width, 2u);
  EXPECT_THROW(packedTexture(read->textures, "other.png"), std::runtime_error);
  std::filesystem::remove(path);
  EXPECT_FALSE(readScenePack(path, error));
  EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << error;
  EXPECT_TRUE(isScenePackPath("a/b.MGPACK"));
  EXPECT_FALSE(isScenePackPath("a/b.gltf"));
}

}  // namespace
}  // namespace memograph::runtime
