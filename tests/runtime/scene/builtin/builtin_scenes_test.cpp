// Invariants of the built-in scenes: what the renderer and the cache benchmarks rely on.
#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "runtime/scene/builtin/builtin_scenes.h"

namespace memograph::runtime {
namespace {

// Checks a generated graph's link structure: every link has exactly one producer, every
// consumed link is produced and every produced link is consumed (no dead nodes the compiler
// would prune, which would make the "expensive" knob lie). Returns a description of the
// first problem, or "".
std::string checkLinks(const std::string& graph) {
  std::map<int, int> producers, consumers;
  const std::regex binding(R"(\b(\w+)([<>])(\d+))");
  for (auto it = std::sregex_iterator(graph.begin(), graph.end(), binding);
       it != std::sregex_iterator(); ++it) {
    const int id = std::stoi((*it)[3]);
    ((*it)[2] == ">" ? producers : consumers)[id]++;
  }
  for (const auto& [id, n] : producers) {
    if (n != 1)
      return "link " + std::to_string(id) + " has " + std::to_string(n) + " producers";
    if (!consumers.count(id))
      return "link " + std::to_string(id) + " is never used";
  }
  for (const auto& [id, n] : consumers) {
    if (!producers.count(id))
      return "link " + std::to_string(id) + " has no producer";
  }
  return "";
}

void expectValidScene(const Scene& scene) {
  ASSERT_FALSE(scene.meshes.empty());
  ASSERT_FALSE(scene.instances.empty());
  ASSERT_FALSE(scene.lights.empty());
  for (const Mesh& mesh : scene.meshes) {
    SCOPED_TRACE(mesh.name);
    ASSERT_FALSE(mesh.positions.empty());
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
    ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    for (std::uint32_t i : mesh.indices)
      ASSERT_LT(i, mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      ASSERT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-4f) << "vertex " << v;
      ASSERT_NEAR(glm::length(glm::vec3(mesh.tangents[v])), 1.0f, 1e-4f) << "vertex " << v;
      ASSERT_NEAR(glm::dot(mesh.normals[v], glm::vec3(mesh.tangents[v])), 0.0f, 1e-3f);
      ASSERT_EQ(std::abs(mesh.tangents[v].w), 1.0f);
    }
    // Faces wind counter-clockwise around their normals (the renderer may cull or flip by
    // winding): the face normal agrees with the vertex normals.
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const auto i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
      const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
      const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
      const glm::vec3 n = glm::cross(e1, e2);
      // Degenerate slivers (sphere poles) have no meaningful winding.
      if (glm::length(n) <= 1e-4f * glm::length(e1) * glm::length(e2))
        continue;
      ASSERT_GT(glm::dot(n, mesh.normals[i0] + mesh.normals[i1] + mesh.normals[i2]), 0.0f)
          << "triangle " << t / 3;
    }
  }
  for (const Instance& instance : scene.instances) {
    ASSERT_LT(instance.mesh, scene.meshes.size());
    ASSERT_LT(instance.material, scene.materials.size());
  }
  std::set<std::string> names;
  for (const MaterialRef& m : scene.materials) {
    SCOPED_TRACE(m.name);
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate material name";
    EXPECT_TRUE(m.graphPath.empty());
    ASSERT_FALSE(m.graphText.empty());
    EXPECT_EQ(m.graphText.rfind("material " + m.name + ";\n", 0), 0u);
    EXPECT_EQ(checkLinks(m.graphText), "");
    // Cacheable (thesis §4.2): only the UV input is read.
    for (const char* input : {"PositionInput", "NormalInput", "TangentInput", "ViewInput",
                              "TimeInput", "VertexColorInput"}) {
      EXPECT_EQ(m.graphText.find(input), std::string::npos) << input;
    }
  }
}

TEST(BuiltinScenes, ClassroomHasAtLeast64DistinctMaterialGraphsAndValidMeshes) {
  const Scene scene = makeBuiltinScene("classroom");
  expectValidScene(scene);
  std::set<std::string> graphs;
  for (const MaterialRef& m : scene.materials)
    graphs.insert(m.graphText);
  EXPECT_GE(graphs.size(), 64u);
  // Every material is used by some instance.
  std::set<std::uint32_t> used;
  for (const Instance& i : scene.instances)
    used.insert(i.material);
  EXPECT_EQ(used.size(), scene.materials.size());
  std::cout << "classroom: " << scene.meshes.size() << " meshes, " << scene.instances.size()
            << " instances, " << graphs.size() << " distinct material graphs, "
            << scene.lights.size() << " lights\n";
}

TEST(BuiltinScenes, ClassroomIsClosedAndLitFromTheCeiling) {
  const Scene scene = makeBuiltinScene("classroom");
  for (const Light& light : scene.lights) {
    EXPECT_EQ(light.type, LightType::Point);
    EXPECT_GT(light.position.y, kClassroom.height * 0.8f);
    EXPECT_LT(light.position.y, kClassroom.height);
  }
  const glm::vec3 eye = scene.camera.position;
  EXPECT_GT(eye.x, 0.0f);
  EXPECT_LT(eye.x, kClassroom.width);
  EXPECT_GT(eye.z, 0.0f);
  EXPECT_LT(eye.z, kClassroom.depth);
}

TEST(BuiltinScenes, LandscapeHasATerrainGridSunAndSky) {
  BuiltinSceneOptions options;
  options.terrainCells = 64;
  const Scene scene = makeBuiltinScene("landscape", options);
  expectValidScene(scene);
  EXPECT_EQ(scene.meshes[0].positions.size(), 65u * 65u);
  EXPECT_EQ(scene.meshes[0].indices.size(), 64u * 64u * 6u);
  EXPECT_LE(scene.materials.size(), 6u);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::Directional);
  EXPECT_LT(scene.lights[0].direction.y, 0.0f);
  EXPECT_GT(scene.environment.constantRadiance.b, 0.0f);
  // The terrain mesh samples the published height function.
  const glm::vec3 p = scene.meshes[0].positions[1234];
  EXPECT_FLOAT_EQ(p.y, landscapeTerrainHeight(p.x, p.z));
  std::cout << "landscape (64 cells): " << scene.instances.size() << " instances, "
            << scene.materials.size() << " materials\n";
}

TEST(BuiltinScenes, DefaultLandscapeTerrainIs256Cells) {
  const Scene scene = makeBuiltinScene("landscape");
  EXPECT_EQ(scene.meshes[0].positions.size(), 257u * 257u);
}

TEST(BuiltinScenes, CostKnobMakesGraphsLonger) {
  BuiltinSceneOptions light, heavy;
  light.materialCost = {2, 0};
  heavy.materialCost = {12, 4};
  const Scene a = makeBuiltinScene("classroom", light);
  const Scene b = makeBuiltinScene("classroom", heavy);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  EXPECT_NE(a.materials[0].graphText.find("Detail=2.0"), std::string::npos);
  EXPECT_NE(b.materials[0].graphText.find("Detail=12.0"), std::string::npos);
  EXPECT_GT(b.materials[0].graphText.size(), a.materials[0].graphText.size());
}

TEST(BuiltinScenes, GenerationIsDeterministic) {
  const Scene a = makeBuiltinScene("classroom");
  const Scene b = makeBuiltinScene("classroom");
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].graphText, b.materials[i].graphText);
  }
  EXPECT_EQ(a.meshes[3].positions, b.meshes[3].positions);
}

TEST(BuiltinScenes, UnknownNameListsTheKnownOnes) {
  try {
    makeBuiltinScene("kitchen");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'kitchen'"), std::string::npos) << message;
    EXPECT_NE(message.find("classroom, landscape"), std::string::npos) << message;
  }
}

TEST(BuiltinScenes, OutOfRangeOptionsAreRejected) {
  BuiltinSceneOptions options;
  options.materialCost.octaves = 0;
  EXPECT_THROW(makeBuiltinScene("classroom", options), std::invalid_argument);
  options = {};
  options.terrainCells = 1;
  EXPECT_THROW(makeBuiltinScene("landscape", options), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime

namespace memograph::runtime {
namespace {

TEST(BuiltinSceneSpec, NameAloneGivesDefaults) {
  std::string error;
  const auto spec = parseBuiltinSceneSpec("landscape", error);
  ASSERT_TRUE(spec.has_value()) << error;
  EXPECT_EQ(spec->name, "landscape");
  EXPECT_EQ(spec->options.terrainCells, BuiltinSceneOptions{}.terrainCells);
}

TEST(BuiltinSceneSpec, OptionsSetTheCostKnobs) {
  std::string error;
  const auto spec = parseBuiltinSceneSpec("classroom:octaves=10,layers=3,terrain=64", error);
  ASSERT_TRUE(spec.has_value()) << error;
  EXPECT_EQ(spec->name, "classroom");
  EXPECT_EQ(spec->options.materialCost.octaves, 10);
  EXPECT_EQ(spec->options.materialCost.layers, 3);
  EXPECT_EQ(spec->options.terrainCells, 64);
}

// ao and bevel (0..128 samples, 0: none) put those nodes into every recipe's graph, links
// whole; without them no graph has either.
TEST(BuiltinSceneSpec, TracedInputKnobsAddTheirNodes) {
  std::string error;
  const auto spec = parseBuiltinSceneSpec("classroom:ao=8,bevel=4", error);
  ASSERT_TRUE(spec.has_value()) << error;
  EXPECT_EQ(spec->options.materialCost.ambientOcclusionSamples, 8);
  EXPECT_EQ(spec->options.materialCost.bevelSamples, 4);
  const Scene traced = makeBuiltinScene("classroom", spec->options);
  const Scene plain = makeBuiltinScene("classroom");
  const MaterialRef& wood = traced.materials[0];
  EXPECT_NE(wood.graphText.find("AmbientOcclusion"), std::string::npos) << wood.graphText;
  EXPECT_NE(wood.graphText.find("Samples=8.0"), std::string::npos) << wood.graphText;
  EXPECT_NE(wood.graphText.find("Bevel"), std::string::npos) << wood.graphText;
  EXPECT_EQ(checkLinks(wood.graphText), "");
  for (const MaterialRef& material : plain.materials) {
    EXPECT_EQ(material.graphText.find("AmbientOcclusion"), std::string::npos) << material.name;
    EXPECT_EQ(material.graphText.find("Bevel"), std::string::npos) << material.name;
  }
  EXPECT_FALSE(parseBuiltinSceneSpec("classroom:ao=129", error).has_value());
  EXPECT_NE(error.find("ao (the samples of an Ambient Occlusion node"), std::string::npos) << error;
  BuiltinSceneOptions options;
  options.materialCost.bevelSamples = -1;
  EXPECT_THROW(makeBuiltinScene("classroom", options), std::invalid_argument);
}

// The classroom samples its emissive panels and windows only when asked (nee=1): measured
// on the H200, its lamps' point lights make that NEE a loss at equal time (builtin_scenes.h).
TEST(BuiltinSceneSpec, TheClassroomSamplesItsEmittersOnlyWhenAsked) {
  std::string error;
  const auto plain = parseBuiltinSceneSpec("classroom", error);
  ASSERT_TRUE(plain.has_value()) << error;
  EXPECT_FALSE(makeBuiltinScene("classroom", plain->options).emissiveLightSampling);
  const auto asked = parseBuiltinSceneSpec("classroom:nee=1", error);
  ASSERT_TRUE(asked.has_value()) << error;
  EXPECT_TRUE(makeBuiltinScene("classroom", asked->options).emissiveLightSampling);
  const auto off = parseBuiltinSceneSpec("landscape:nee=0", error);
  ASSERT_TRUE(off.has_value()) << error;
  EXPECT_FALSE(makeBuiltinScene("landscape", off->options).emissiveLightSampling);
}

TEST(BuiltinSceneSpec, BadOptionsNameTheProblem) {
  std::string error;
  EXPECT_FALSE(parseBuiltinSceneSpec("classroom:detail=3", error).has_value());
  EXPECT_NE(error.find("unknown option 'detail'"), std::string::npos) << error;
  EXPECT_NE(error.find("octaves, layers, terrain, nee"), std::string::npos) << error;
  EXPECT_FALSE(parseBuiltinSceneSpec("classroom:nee=2", error).has_value());
  EXPECT_NE(error.find("nee is 0"), std::string::npos) << error;
  EXPECT_FALSE(parseBuiltinSceneSpec("classroom:octaves=many", error).has_value());
  EXPECT_NE(error.find("'octaves=many'"), std::string::npos) << error;
  EXPECT_FALSE(parseBuiltinSceneSpec("classroom:octaves", error).has_value());
  EXPECT_FALSE(parseBuiltinSceneSpec(":octaves=3", error).has_value());
}

// onGeometry hears the totals after every mesh and may stop the build: the render command's
// device check relies on it to refuse the full city on lavapipe before most of it is made.
TEST(BuiltinScenes, GeometryCheckHearsEveryMeshAndCanStopTheBuild) {
  struct Stop {};
  BuiltinSceneOptions options;
  options.terrainCells = 64;
  std::uint64_t calls = 0, lastVertices = 0, lastTriangles = 0;
  options.onGeometry = [&](std::uint64_t vertices, std::uint64_t triangles) {
    EXPECT_GE(vertices, lastVertices);
    EXPECT_GE(triangles, lastTriangles);
    ++calls;
    lastVertices = vertices;
    lastTriangles = triangles;
  };
  const Scene scene = makeLandscapeScene(options);
  EXPECT_EQ(calls, scene.meshes.size());
  std::uint64_t vertices = 0, triangles = 0;
  for (const Mesh& mesh : scene.meshes) {
    vertices += mesh.positions.size();
    triangles += mesh.indices.size() / 3;
  }
  EXPECT_EQ(lastVertices, vertices);
  EXPECT_EQ(lastTriangles, triangles);

  std::uint64_t callsUntilStop = 0;
  options.onGeometry = [&](std::uint64_t, std::uint64_t) {
    if (++callsUntilStop == 2)
      throw Stop{};
  };
  EXPECT_THROW(makeCityScene(options), Stop);
  EXPECT_EQ(callsUntilStop, 2u);
}

}  // namespace
}  // namespace memograph::runtime
