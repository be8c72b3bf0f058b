// Scene import: small glTF and OBJ files written here by hand, and the error paths.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "tools/io/base64.h"
#include "tools/io/scene_import.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;
using compiler::Diagnostics;

template <typename T>
void append(std::vector<unsigned char>& bytes, std::initializer_list<T> values) {
  for (T v : values) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    bytes.insert(bytes.end(), b, b + sizeof(T));
  }
}

// A unit quad in the xy plane (normal +z, UVs 0..1, no tangents), used by two materials;
// a parent node with two children instancing it; a camera; a point and a directional light.
std::vector<unsigned char> quadBuffer() {
  std::vector<unsigned char> buffer;
  append<float>(buffer, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});  // positions, 48 bytes
  append<float>(buffer, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});  // normals, 48 bytes
  append<float>(buffer, {0, 0, 1, 0, 1, 1, 0, 1});              // uvs, 32 bytes
  append<std::uint16_t>(buffer, {0, 1, 2, 0, 2, 3});            // indices, 12 bytes
  return buffer;
}

// `bufferSource` completes the buffer object: a data URI for .gltf, nothing for .glb.
std::string quadJson(const std::string& bufferSource) {
  const std::string primitive =
      R"("attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3)";
  return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"name": "Bulb", "type": "point", "color": [1.0, 0.5, 0.25], "intensity": 4.0},
    {"name": "Sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 2.0}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 3, 4, 5, 6]}],
  "nodes": [
    {"name": "Parent", "translation": [10, 0, 0], "children": [1, 2]},
    {"name": "QuadA", "mesh": 0},
    {"name": "QuadB", "mesh": 0, "translation": [0, 2, 0], "scale": [2, 2, 2]},
    {"name": "Window", "mesh": 1, "translation": [0, 0, -3]},
    {"name": "Cam", "camera": 0, "translation": [0, 1, 5]},
    {"name": "BulbNode", "translation": [1, 3, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "SunNode", "rotation": [-0.70710678, 0, 0, 0.70710678],
     "extensions": {"KHR_lights_punctual": {"light": 1}}}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100}}],
  "materials": [{"name": "Wood"}, {"name": "Glass"}],
  "meshes": [
    {"name": "Quad", "primitives": [{)" +
         primitive + R"(, "material": 0}]},
    {"name": "Pane", "primitives": [{)" +
         primitive + R"(, "material": 1}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 32},
    {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
  "buffers": [{"byteLength": 140)" +
         bufferSource + R"(}]
})";
}

std::string quadGltf() {
  return quadJson(R"(, "uri": "data:application/octet-stream;base64,)" +
                  base64Encode(quadBuffer()) + "\"");
}

// The same scene as a binary glTF: a 12-byte header, a JSON chunk and a BIN chunk, each
// padded to four bytes (glTF 2.0 §4.4).
std::string quadGlb() {
  std::string json = quadJson("");
  while (json.size() % 4)
    json += ' ';
  std::vector<unsigned char> bin = quadBuffer();
  while (bin.size() % 4)
    bin.push_back(0);
  std::vector<unsigned char> out;
  const auto u32 = [&](std::uint32_t v) { append<std::uint32_t>(out, {v}); };
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534A);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  u32(static_cast<std::uint32_t>(bin.size()));
  u32(0x004E4942);  // "BIN"
  out.insert(out.end(), bin.begin(), bin.end());
  return std::string(out.begin(), out.end());
}

// A cube without normals, with UVs, using material Red from its .mtl.
const char* kCubeObj = R"(mtllib cube.mtl
o Cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl Red
f 1/1 4/4 3/3 2/2
f 5/1 6/2 7/3 8/4
f 1/1 2/2 6/3 5/4
f 4/1 8/2 7/3 3/4
f 1/1 5/2 8/3 4/4
f 2/1 3/2 7/3 6/4
)";

class SceneImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("memograph_import_" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    fs::create_directories(dir / "materials");
    std::ofstream(dir / "materials" / "Wood.mgraph") << "material Wood;\n";
    std::ofstream(dir / "materials" / "Red.mgraph") << "material Red;\n";
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
  std::string materials() const { return (dir / "materials").string(); }
  fs::path dir;
};

TEST_F(SceneImportTest, GltfGivesSharedMeshesInstancesCameraLightsAndMaterials) {
  const std::string path = write("quad.gltf", quadGltf());
  Diagnostics diagnostics;
  const auto scene = importScene(path, materials(), diagnostics);
  ASSERT_TRUE(scene.has_value()) << compiler::formatDiagnostics(diagnostics);

  ASSERT_EQ(scene->meshes.size(), 2u);
  ASSERT_EQ(scene->instances.size(), 3u);
  const runtime::Mesh& quad = scene->meshes[scene->instances[0].mesh];
  EXPECT_EQ(quad.indices.size(), 6u);
  ASSERT_EQ(quad.uvs.size(), quad.positions.size());
  ASSERT_EQ(quad.tangents.size(), quad.positions.size());  // generated: the file has none
  for (std::size_t v = 0; v < quad.positions.size(); ++v) {
    EXPECT_NEAR(glm::dot(quad.normals[v], glm::vec3(0, 0, 1)), 1.0f, 1e-5f);
    // u grows along +x, so the tangent is +x.
    EXPECT_NEAR(quad.tangents[v].x, 1.0f, 1e-5f);
    EXPECT_EQ(std::abs(quad.tangents[v].w), 1.0f);
  }
  // Both children of Parent share the mesh; their world transforms compose the hierarchy.
  EXPECT_EQ(scene->instances[0].mesh, scene->instances[1].mesh);
  const glm::vec4 cornerA = scene->instances[0].objectToWorld * glm::vec4(1, 1, 0, 1);
  const glm::vec4 cornerB = scene->instances[1].objectToWorld * glm::vec4(1, 1, 0, 1);
  EXPECT_EQ(glm::vec3(cornerA), glm::vec3(11, 1, 0));
  EXPECT_EQ(glm::vec3(cornerB), glm::vec3(12, 4, 0));

  // Wood has a graph; Glass does not and gets the visible default, with a warning.
  const runtime::MaterialRef& wood = scene->materials[scene->instances[0].material];
  EXPECT_EQ(wood.name, "Wood");
  EXPECT_EQ(fs::path(wood.graphPath), dir / "materials" / "Wood.mgraph");
  const runtime::MaterialRef& glass = scene->materials[scene->instances[2].material];
  EXPECT_EQ(glass.name, kMissingMaterialName);
  EXPECT_NE(glass.graphText.find("CheckerTexture"), std::string::npos);
  bool warned = false;
  for (const auto& d : diagnostics.all()) {
    warned |= d.severity == compiler::Severity::Warning &&
              d.message.find("'Glass' has no graph") != std::string::npos;
  }
  EXPECT_TRUE(warned) << compiler::formatDiagnostics(diagnostics);
  EXPECT_FALSE(diagnostics.hasErrors());

  // Camera at (0, 1, 5) looking down -z with the file's vertical field of view.
  EXPECT_NEAR(glm::distance(scene->camera.position, glm::vec3(0, 1, 5)), 0.0f, 1e-5f);
  const glm::vec3 view = glm::normalize(scene->camera.target - scene->camera.position);
  EXPECT_NEAR(view.z, -1.0f, 1e-5f);
  EXPECT_NEAR(scene->camera.verticalFovDegrees, glm::degrees(0.8f), 0.05f);

  ASSERT_EQ(scene->lights.size(), 2u);
  const runtime::Light* bulb = nullptr;
  const runtime::Light* sun = nullptr;
  for (const auto& l : scene->lights)
    (l.type == runtime::LightType::Point ? bulb : sun) = &l;
  ASSERT_TRUE(bulb && sun);
  EXPECT_NEAR(glm::distance(bulb->position, glm::vec3(1, 3, 1)), 0.0f, 1e-5f);
  EXPECT_NEAR(bulb->intensity.r / bulb->intensity.g, 2.0f, 1e-4f);  // colour ratio kept
  EXPECT_GT(bulb->intensity.r, 0.0f);
  EXPECT_NEAR(glm::distance(sun->direction, glm::vec3(0, -1, 0)), 0.0f, 1e-4f);
}

// The Blender scene export's sidecar (docs/guide/blender.md, "Scene export"): Z-up root, light
// units (/ 683), the named camera, the world, texture spaces, emitters and area lights.
TEST_F(SceneImportTest, BlenderSidecarConvertsUnitsWorldTextureSpaceAndAreaLights) {
  const std::string path = write("quad.gltf", quadGltf());
  Diagnostics plainDiagnostics;
  const auto plain = importScene(path, materials(), plainDiagnostics);
  ASSERT_TRUE(plain.has_value());
  write("quad.memograph",
        "memograph-blender-scene 1\n# comment\nup z\nlighting SPEC 683\ncamera Cam\n"
        "world color 0.5 0.25 1 strength 2\ntexspace 1 2 3 4 5 6 Quad\n"
        "emitter 3 3 3 Wood\nsome-future-statement 1 2\n"
        "area SQUARE 0.5 0.5 50 1 1 1 1 0 0 0 0 1 0 0 0 0 1 0 0 0 3 1 Panel Light\n");
  Diagnostics diagnostics;
  const auto scene = importScene(path, materials(), diagnostics);
  ASSERT_TRUE(scene.has_value()) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(scene->lights.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(scene->lights[i].intensity.r * 683.0f, plain->lights[i].intensity.r, 1e-3f);
  }
  // Z-up to y-up: Blender's (x, y, z) is memograph's (x, z, -y).
  const runtime::Light& bulb =
      scene->lights[0].type == runtime::LightType::Point ? scene->lights[0] : scene->lights[1];
  EXPECT_NEAR(glm::distance(bulb.position, glm::vec3(1, 1, -3)), 0.0f, 1e-5f);
  EXPECT_EQ(scene->environment.constantRadiance, glm::vec3(1.0f, 0.5f, 2.0f));
  const runtime::Mesh& quad = scene->meshes[scene->instances[0].mesh];
  EXPECT_TRUE(quad.hasTextureSpace);
  EXPECT_EQ(quad.textureSpaceLocation, glm::vec3(1, 2, 3));
  EXPECT_EQ(quad.textureSpaceSize, glm::vec3(4, 5, 6));
  EXPECT_EQ(scene->materials[scene->instances[0].material].emissionEstimate, glm::vec3(3.0f));
  // The area light: one more instance, a 0.5 m quad whose front (-z, Blender) emits
  // P / (4 A) = 50 W, cast no shadow, placed at Blender (0, 0, 3) = memograph (0, 3, 0).
  ASSERT_EQ(scene->instances.size(), plain->instances.size() + 1);
  const runtime::Instance& area = scene->instances.back();
  EXPECT_FALSE(area.castsShadow);
  EXPECT_NEAR(glm::distance(glm::vec3(area.objectToWorld[3]), glm::vec3(0, 3, 0)), 0.0f, 1e-5f);
  const glm::vec3 down = glm::vec3(area.objectToWorld * glm::vec4(0, 0, -1, 0));
  EXPECT_NEAR(glm::distance(down, glm::vec3(0, -1, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(scene->materials[area.material].emissionEstimate, glm::vec3(50.0f));
  EXPECT_NE(scene->materials[area.material].graphText.find("Backfacing"), std::string::npos);
  // An `emitter` line is an estimate (NEE evaluates the graph); the area quad's front emits
  // exactly its radiance; `emitter_constant` declares the material's exact emission.
  using Kind = runtime::MaterialRef::EmissionKind;
  EXPECT_EQ(scene->materials[scene->instances[0].material].emissionKind, Kind::Graph);
  EXPECT_EQ(scene->materials[area.material].emissionKind, Kind::ConstantFront);
  EXPECT_FALSE(diagnostics.hasErrors());
  write("quad.memograph", "memograph-blender-scene 1\nemitter_constant 3 3 3 Wood\n");
  Diagnostics constantDiagnostics;
  const auto constant = importScene(path, materials(), constantDiagnostics);
  ASSERT_TRUE(constant.has_value()) << compiler::formatDiagnostics(constantDiagnostics);
  const runtime::MaterialRef& wood = constant->materials[constant->instances[0].material];
  EXPECT_EQ(wood.emissionEstimate, glm::vec3(3.0f));
  EXPECT_EQ(wood.emissionKind, Kind::Constant);

  write("quad.memograph", "memograph-blender-scene 1\nlighting SPEC\n");
  Diagnostics bad;
  EXPECT_FALSE(importScene(path, materials(), bad).has_value());
  EXPECT_NE(compiler::formatDiagnostics(bad).find("line 2"), std::string::npos)
      << compiler::formatDiagnostics(bad);
}

// Cycles' Filter Glossy travels in the sidecar (`render filter_glossy F`, docs/guide/blender.md);
// a sidecar without the line (an older export) means 0, off; a negative or non-numeric value
// is an error naming the line.
TEST_F(SceneImportTest, BlenderSidecarCarriesFilterGlossy) {
  const std::string path = write("quad.gltf", quadGltf());
  write("quad.memograph", "memograph-blender-scene 1\nup z\n");
  Diagnostics oldDiagnostics;
  const auto old = importScene(path, materials(), oldDiagnostics);
  ASSERT_TRUE(old.has_value()) << compiler::formatDiagnostics(oldDiagnostics);
  EXPECT_EQ(old->filterGlossy, 0.0f);

  write("quad.memograph", "memograph-blender-scene 1\nup z\nrender filter_glossy 0.75\n");
  Diagnostics diagnostics;
  const auto scene = importScene(path, materials(), diagnostics);
  ASSERT_TRUE(scene.has_value()) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(scene->filterGlossy, 0.75f);

  for (const char* value : {"-1", "nan", "glossy", ""}) {
    write("quad.memograph",
          std::string("memograph-blender-scene 1\nrender filter_glossy ") + value + "\n");
    Diagnostics bad;
    EXPECT_FALSE(importScene(path, materials(), bad).has_value()) << value;
    EXPECT_NE(compiler::formatDiagnostics(bad).find("line 2"), std::string::npos)
        << compiler::formatDiagnostics(bad);
  }
}

TEST_F(SceneImportTest, BinaryGltfImportsLikeTheTextForm) {
  Diagnostics diagnostics;
  const auto glb = importScene(write("quad.glb", quadGlb()), materials(), diagnostics);
  ASSERT_TRUE(glb.has_value()) << compiler::formatDiagnostics(diagnostics);
  const auto gltf = importScene(write("quad.gltf", quadGltf()), materials(), diagnostics);
  ASSERT_TRUE(gltf.has_value());
  ASSERT_EQ(glb->instances.size(), gltf->instances.size());
  ASSERT_EQ(glb->meshes.size(), gltf->meshes.size());
  for (std::size_t i = 0; i < glb->instances.size(); ++i) {
    EXPECT_EQ(glb->instances[i].objectToWorld, gltf->instances[i].objectToWorld);
  }
  EXPECT_EQ(glb->meshes[0].positions, gltf->meshes[0].positions);
  EXPECT_EQ(glb->camera.position, gltf->camera.position);
  EXPECT_EQ(glb->lights.size(), 2u);
}

TEST_F(SceneImportTest, ObjGetsNormalsTangentsAndItsMtlMaterial) {
  write("cube.mtl", "newmtl Red\nKd 1 0 0\n");
  const std::string path = write("cube.obj", kCubeObj);
  Diagnostics diagnostics;
  const auto scene = importScene(path, materials(), diagnostics);
  ASSERT_TRUE(scene.has_value()) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(scene->meshes.size(), 1u);
  const runtime::Mesh& cube = scene->meshes[0];
  EXPECT_EQ(cube.indices.size(), 36u);
  ASSERT_EQ(cube.normals.size(), cube.positions.size());
  ASSERT_EQ(cube.tangents.size(), cube.positions.size());
  for (const glm::vec3& n : cube.normals)
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
  ASSERT_EQ(scene->instances.size(), 1u);
  EXPECT_EQ(scene->materials[scene->instances[0].material].name, "Red");
  EXPECT_FALSE(scene->materials[scene->instances[0].material].graphPath.empty());
  // No camera in an OBJ: the default one looks at the cube's centre from outside it.
  EXPECT_NEAR(glm::distance(scene->camera.target, glm::vec3(0.5f)), 0.0f, 1e-5f);
  EXPECT_GT(glm::distance(scene->camera.position, glm::vec3(0.5f)), 1.0f);
}

TEST_F(SceneImportTest, WithoutMaterialsFolderEveryMaterialIsTheDefault) {
  const std::string path = write("quad.gltf", quadGltf());
  Diagnostics diagnostics;
  const auto scene = importScene(path, "", diagnostics);
  ASSERT_TRUE(scene.has_value());
  ASSERT_EQ(scene->materials.size(), 1u);
  EXPECT_EQ(scene->materials[0].name, kMissingMaterialName);
  EXPECT_FALSE(diagnostics.hasErrors());
}

TEST_F(SceneImportTest, MissingFileIsAnError) {
  Diagnostics diagnostics;
  EXPECT_FALSE(importScene((dir / "nothing.gltf").string(), "", diagnostics).has_value());
  ASSERT_EQ(diagnostics.errorCount(), 1u);
  EXPECT_EQ(diagnostics.all()[0].message, "no such file");
}

TEST_F(SceneImportTest, MissingMaterialsFolderIsAnError) {
  const std::string path = write("quad.gltf", quadGltf());
  Diagnostics diagnostics;
  EXPECT_FALSE(importScene(path, (dir / "nope").string(), diagnostics).has_value());
  EXPECT_NE(diagnostics.all()[0].message.find("materials folder"), std::string::npos);
}

TEST_F(SceneImportTest, BrokenFilesAreErrorsNotCrashes) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"truncated.gltf", quadGltf().substr(0, 300)},
      {"garbage.glb", std::string("glTF\x02\0\0\0garbage", 15)},
      {"points.obj", "v 0 0 0\nv 1 0 0\np 1 2\n"},
      {"unknown.xyz123", "hello"},
      {"empty.obj", ""},
  };
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    Diagnostics diagnostics;
    EXPECT_FALSE(importScene(write(name, text), "", diagnostics).has_value());
    ASSERT_TRUE(diagnostics.hasErrors());
    EXPECT_EQ(fs::path(diagnostics.all().back().file).filename(), name);
    std::cout << compiler::formatDiagnostics(diagnostics);
  }
}

// assimp 5.2's MTL reader crashes on some bytes (found by the OBJ import fuzzer: an OBJ named
// as its own material library). memograph reads only `usemtl` names, so an OBJ import opens
// nothing but the OBJ, whatever a library is called: these import their triangle.
TEST_F(SceneImportTest, AnObjsMaterialLibrariesAreNeverParsedWhateverTheirName) {
  const std::string crashing =
      std::string("mtllib self.obj\nv 0 0 1\nv 1 0 0\nv\xe0\xcf\xf7\x04 0 0 0\ndisp0  0");
  write("library.obj", crashing);
  write("library.mtl", crashing);
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Red\nf 1 2 3\n";
  for (const char* library : {"library.obj", "library.mtl", "self.obj"}) {
    SCOPED_TRACE(library);
    const std::string path = write("self.obj", std::string("mtllib ") + library + "\n" + triangle);
    Diagnostics diagnostics;
    const auto scene = importScene(path, materials(), diagnostics);
    ASSERT_TRUE(scene.has_value()) << compiler::formatDiagnostics(diagnostics);
    ASSERT_EQ(scene->instances.size(), 1u);
    EXPECT_EQ(scene->materials[scene->instances[0].material].name, "Red");
  }
}

}  // namespace
}  // namespace memograph::io
