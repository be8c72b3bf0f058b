// Mesh LODs (seeds/001 §3.3.1; runtime/scene/builtin/mesh_lods.h): each level has fewer
// triangles than the one before within an error that grows, over the mesh's own vertices
// and attributes; a level records the longest part it removes whole; the same mesh gives the
// same LODs on every run; the city's buildings get them and its shared props and moving flags
// do not; small or broken meshes get none.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/mesh_builder.h"
#include "runtime/scene/builtin/mesh_lods.h"

namespace memograph::runtime {
namespace {

// A wall of 10 x 8 windows, each six boxes as the city's (a sill, a lintel, two jambs, a
// mullion, a pane): the geometry the simplifier should thin.
Mesh windowedWall() {
  Mesh mesh;
  mesh.name = "wall";
  appendBox(mesh, {-15.0f, 0.0f, -0.5f}, {15.0f, 26.0f, 0.0f});
  for (int floor = 0; floor < 8; ++floor)
    for (int w = 0; w < 10; ++w) {
      const float x = -13.5f + 3.0f * float(w), y = 0.8f + 3.2f * float(floor);
      appendBox(mesh, {x - 0.75f, y - 0.12f, 0.0f}, {x + 0.75f, y, 0.23f});
      appendBox(mesh, {x - 0.7f, y + 1.68f, 0.0f}, {x + 0.7f, y + 1.8f, 0.18f});
      appendBox(mesh, {x - 0.7f, y, 0.0f}, {x - 0.58f, y + 1.68f, 0.18f});
      appendBox(mesh, {x + 0.58f, y, 0.0f}, {x + 0.7f, y + 1.68f, 0.18f});
      appendBox(mesh, {x - 0.06f, y, 0.0f}, {x + 0.06f, y + 1.68f, 0.11f});
      appendBox(mesh, {x - 0.58f, y, -0.12f}, {x + 0.58f, y + 1.68f, -0.08f});
    }
  return mesh;
}

bool sameMesh(const Mesh& a, const Mesh& b) {
  const auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
  return a.positions.size() == b.positions.size() && a.indices == b.indices &&
         std::memcmp(a.positions.data(), b.positions.data(), bytes(a.positions)) == 0 &&
         std::memcmp(a.normals.data(), b.normals.data(), bytes(a.normals)) == 0 &&
         std::memcmp(a.uvs.data(), b.uvs.data(), bytes(a.uvs)) == 0;
}

TEST(MeshLods, EachLevelShrinksWithinAGrowingErrorOverTheMeshsOwnVertices) {
  const Mesh wall = windowedWall();
  const MeshLodSettings settings;
  const std::vector<MeshLod> lods = buildMeshLods(wall, settings);
  ASSERT_GE(lods.size(), 2u) << "the windows' frames should thin at least twice";
  // The extent meshoptimizer scales the targets by: the wall's largest side, 30 m.
  const float extent = 30.0f;
  // The original's vertices, to find each level's among them.
  std::set<std::tuple<float, float, float, float, float, float, float, float>> vertices;
  for (std::size_t v = 0; v < wall.positions.size(); ++v)
    vertices.insert({wall.positions[v].x, wall.positions[v].y, wall.positions[v].z,
                     wall.normals[v].x, wall.normals[v].y, wall.normals[v].z, wall.uvs[v].x,
                     wall.uvs[v].y});
  std::size_t finerTriangles = wall.indices.size() / 3;
  float finerError = 0.0f;
  for (std::size_t l = 0; l < lods.size(); ++l) {
    const Mesh& mesh = lods[l].mesh;
    const std::size_t triangles = mesh.indices.size() / 3;
    EXPECT_GT(triangles, 0u);
    EXPECT_LE(double(triangles), settings.maxTriangleFraction * double(finerTriangles))
        << "level " << l + 1;
    EXPECT_GE(lods[l].error, finerError) << "level " << l + 1;
    EXPECT_LE(lods[l].error, settings.relativeErrors[l] * extent * 1.001f) << "level " << l + 1;
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
    EXPECT_EQ(mesh.tangents.size(), 0u);
    for (const std::uint32_t index : mesh.indices)
      ASSERT_LT(index, mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
      EXPECT_TRUE(vertices.count({mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z,
                                  mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z,
                                  mesh.uvs[v].x, mesh.uvs[v].y}))
          << "level " << l + 1 << " vertex " << v << " is none of the mesh's";
    finerTriangles = triangles;
    finerError = lods[l].error;
  }
  // The coarsest level has lost the window frames: a few percent of the wall's triangles.
  EXPECT_LT(lods.back().mesh.indices.size(), wall.indices.size() / 10);
}

// A level that collapses a part whole records the part's longest side, which a viewer sees
// go, beside the simplifier's error, its thickness: the wall's window frames (1.4 to 1.8 m
// long, at most 0.23 m out) are gone by the coarsest level, and no level removes more than a
// window's height (a jamb welded to its lintel, 1.8 m).
TEST(MeshLods, ALevelRecordsTheLongestPartItRemovesWhole) {
  const std::vector<MeshLod> lods = buildMeshLods(windowedWall());
  ASSERT_FALSE(lods.empty());
  float finer = 0.0f;
  for (std::size_t l = 0; l < lods.size(); ++l) {
    std::printf("level %zu: %zu triangles, error %.3f m, removed part %.3f m\n", l + 1,
                lods[l].mesh.indices.size() / 3, lods[l].error, lods[l].removedPart);
    EXPECT_GE(lods[l].removedPart, finer) << "level " << l + 1;
    EXPECT_LE(lods[l].removedPart, 1.8f + 1e-4f) << "level " << l + 1;
    finer = lods[l].removedPart;
  }
  // The first level that removes a window's parts (their frames stand 0.23 m out at most)
  // records their length, many times the simplifier's error.
  const auto first = std::find_if(lods.begin(), lods.end(),
                                  [](const MeshLod& lod) { return lod.removedPart > 0.0f; });
  ASSERT_NE(first, lods.end());
  EXPECT_GE(first->removedPart, 1.5f - 1e-4f);
  EXPECT_GT(first->removedPart, 4.0f * first->error);
}

TEST(MeshLods, TheSameMeshGivesTheSameLods) {
  const Mesh wall = windowedWall();
  const std::vector<MeshLod> a = buildMeshLods(wall), b = buildMeshLods(wall);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t l = 0; l < a.size(); ++l) {
    EXPECT_TRUE(sameMesh(a[l].mesh, b[l].mesh)) << "level " << l + 1;
    EXPECT_EQ(a[l].error, b[l].error);
  }
}

TEST(MeshLods, SmallOrBrokenMeshesGetNone) {
  Mesh box;
  appendBox(box, glm::vec3(0.0f), glm::vec3(1.0f));
  EXPECT_TRUE(buildMeshLods(box).empty()) << "12 triangles: nothing to gain";
  Mesh broken = windowedWall();
  broken.indices[7] = static_cast<std::uint32_t>(broken.positions.size());
  EXPECT_TRUE(buildMeshLods(broken).empty());
  Mesh noNormals = windowedWall();
  noNormals.normals.clear();
  EXPECT_TRUE(buildMeshLods(noNormals).empty());
  Scene scene;
  scene.meshes.push_back(box);
  EXPECT_THROW(addMeshLods(scene, {1}), std::invalid_argument);
}

TEST(MeshLods, TheCitysBuildingsHaveThemOnlyWhenAskedAndItsPropsAndFlagsNot) {
  BuiltinSceneOptions options;
  options.cityScale = 0.02;
  // Not asked for (a render that shows none): none built.
  EXPECT_TRUE(makeBuiltinScene("city", options).meshLods.empty());
  options.meshLods = true;
  const Scene a = makeBuiltinScene("city", options), b = makeBuiltinScene("city", options);
  ASSERT_EQ(a.meshLods.size(), a.meshes.size());
  std::size_t withLods = 0, buildings = 0;
  for (std::size_t m = 0; m < a.meshes.size(); ++m) {
    const bool building = a.meshes[m].name.rfind("building_", 0) == 0;
    if (!building) {
      EXPECT_TRUE(a.meshLods[m].empty()) << a.meshes[m].name;
    }
    buildings += building;
    withLods += !a.meshLods[m].empty();
    // Each level keeps at most the settings' fraction of the finer one's triangles.
    for (std::size_t l = 0; l < a.meshLods[m].size(); ++l) {
      const Mesh& finer = l == 0 ? a.meshes[m] : a.meshLods[m][l - 1].mesh;
      EXPECT_LE(double(a.meshLods[m][l].mesh.indices.size()),
                MeshLodSettings{}.maxTriangleFraction * double(finer.indices.size()))
          << a.meshes[m].name << " level " << l + 1;
    }
    // Built at scene creation, the same on every run.
    ASSERT_EQ(a.meshLods[m].size(), b.meshLods[m].size());
    for (std::size_t l = 0; l < a.meshLods[m].size(); ++l)
      EXPECT_TRUE(sameMesh(a.meshLods[m][l].mesh, b.meshLods[m][l].mesh));
  }
  // Every building, those whose frames lose only a tenth of their triangles within the first
  // target included: that level is skipped, and the next target taken (before, the chain
  // stopped there, and 797 of the full city's 2,000 buildings, 22 % of its triangles, had no
  // LOD at all).
  EXPECT_EQ(withLods, buildings);
  EXPECT_EQ(buildings, 40u);
  for (const std::uint32_t flag : a.animatedMeshes)
    EXPECT_TRUE(a.meshLods[flag].empty());
}

}  // namespace
}  // namespace memograph::runtime
