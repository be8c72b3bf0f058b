// The mesh helpers produce the frames the material UV derivatives and normal maps rely on.
#include <gtest/gtest.h>

#include "runtime/scene/builtin/mesh_builder.h"

namespace memograph::runtime {
namespace {

// For every triangle: the tangent points along dP/du and the bitangent w·(n × t) along
// dP/dv, as MaterialInputs documents.
void expectTangentsFollowUv(const Mesh& mesh) {
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const auto i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
    const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
    const glm::vec2 d1 = mesh.uvs[i1] - mesh.uvs[i0], d2 = mesh.uvs[i2] - mesh.uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-9f)
      continue;
    const glm::vec3 dpdu = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 dpdv = (e2 * d1.x - e1 * d2.x) / det;
    const glm::vec4 tangent = mesh.tangents[i0];
    const glm::vec3 bitangent = tangent.w * glm::cross(mesh.normals[i0], glm::vec3(tangent));
    EXPECT_GT(glm::dot(glm::vec3(tangent), dpdu), 0.0f) << "triangle " << t / 3;
    EXPECT_GT(glm::dot(bitangent, dpdv), 0.0f) << "triangle " << t / 3;
  }
}

TEST(MeshBuilder, BoxHasOutwardFacesWorldUnitUvsAndUvAlignedTangents) {
  Mesh mesh;
  appendBox(mesh, {0, 0, 0}, {2, 1, 0.5f}, UvScale{0.5f});
  computeTangents(mesh);
  ASSERT_EQ(mesh.positions.size(), 24u);
  ASSERT_EQ(mesh.indices.size(), 36u);
  const glm::vec3 centre{1, 0.5f, 0.25f};
  for (std::size_t v = 0; v < 24; ++v) {
    EXPECT_GT(glm::dot(mesh.normals[v], mesh.positions[v] - centre), 0.0f);
  }
  // The +y face (vertices 8..11) is 2 m × 0.5 m: at 0.5 m per UV unit it spans 4 × 1.
  float maxU = 0, maxV = 0;
  for (std::size_t v = 8; v < 12; ++v) {
    maxU = std::max(maxU, mesh.uvs[v].x);
    maxV = std::max(maxV, mesh.uvs[v].y);
  }
  EXPECT_FLOAT_EQ(maxU, 4.0f);
  EXPECT_FLOAT_EQ(maxV, 1.0f);
  expectTangentsFollowUv(mesh);
}

TEST(MeshBuilder, FlatHeightfieldFacesUpWithTangentsAlongX) {
  const Mesh mesh = makeHeightfield("flat", -1, -1, 1, 1, 4, [](float, float) { return 2.0f; });
  ASSERT_EQ(mesh.positions.size(), 25u);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    EXPECT_NEAR(mesh.normals[v].y, 1.0f, 1e-6f);
    EXPECT_NEAR(mesh.tangents[v].x, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(mesh.positions[v].y, 2.0f);
  }
  expectTangentsFollowUv(mesh);
}

TEST(MeshBuilder, SlopedHeightfieldNormalsMatchTheGradient) {
  // y = 0.5 x: the normal is (-0.5, 1, 0) normalized.
  const Mesh mesh =
      makeHeightfield("slope", 0, 0, 4, 4, 8, [](float x, float) { return 0.5f * x; });
  const glm::vec3 expected = glm::normalize(glm::vec3(-0.5f, 1.0f, 0.0f));
  for (const glm::vec3& n : mesh.normals)
    EXPECT_NEAR(glm::dot(n, expected), 1.0f, 1e-5f);
  expectTangentsFollowUv(mesh);
}

TEST(MeshBuilder, MirroredUvsGiveNegativeHandedness) {
  Mesh mesh;
  appendBox(mesh, {0, 0, 0}, {1, 1, 1});
  for (glm::vec2& uv : mesh.uvs)
    uv.x = -uv.x;
  computeTangents(mesh);
  for (const glm::vec4& t : mesh.tangents)
    EXPECT_EQ(t.w, -1.0f);
  expectTangentsFollowUv(mesh);
}

TEST(MeshBuilder, SolidsHaveConsistentFrames) {
  Mesh mesh;
  appendCylinder(mesh, {0, 0, 0}, 0.5f, 2.0f, 12);
  appendCone(mesh, {0, 2, 0}, 1.0f, 2.0f, 12);
  appendDeformedSphere(mesh, {3, 0, 0}, {1, 1, 1}, 8, 16, [](glm::vec3) { return 1.0f; });
  computeTangents(mesh);
  ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    EXPECT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(mesh.normals[v], glm::vec3(mesh.tangents[v])), 0.0f, 1e-4f);
  }
}

TEST(MeshBuilder, NoUvsMeansNoTangents) {
  Mesh mesh;
  appendBox(mesh, {0, 0, 0}, {1, 1, 1});
  mesh.uvs.clear();
  computeTangents(mesh);
  EXPECT_TRUE(mesh.tangents.empty());
}

}  // namespace
}  // namespace memograph::runtime
