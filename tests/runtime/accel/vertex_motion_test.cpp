// The vertex pass (vertex_motion.comp; seeds/001 §3.3.1) against the host's evaluation of
// the same motion (vertex_motion.h): the moved positions, the normals of the moved
// triangles turned to the mesh's own side, the texture coordinates left in place, and only
// the meshes the frame needs moved.
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/accel/animated_blases.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/shaders/accel/vertex_motion.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {
namespace {

// A cloth of `columns` x `rows` quads in the z = 0 plane, along +x from x = 0, its normals
// +z; `flipped` winds its triangles the other way round (their normals then face -z, the
// mesh's own side still +z).
Mesh cloth(int columns, int rows, bool flipped) {
  Mesh mesh;
  for (int r = 0; r <= rows; ++r) {
    for (int c = 0; c <= columns; ++c) {
      const float u = float(c) / float(columns), v = float(r) / float(rows);
      mesh.positions.push_back({2.4f * u, 1.5f * v, 0.0f});
      mesh.normals.push_back({0.0f, 0.0f, 1.0f});
      mesh.uvs.push_back({u, v});
    }
  }
  const auto row = static_cast<std::uint32_t>(columns + 1);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const auto i = static_cast<std::uint32_t>(r) * row + static_cast<std::uint32_t>(c);
      if (flipped)
        mesh.indices.insert(mesh.indices.end(), {i, i + row, i + 1, i + 1, i + row, i + row + 1});
      else
        mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + row, i + 1, i + row + 1, i + row});
    }
  }
  return mesh;
}

// The host's moved vertices: positions, and area-weighted triangle normals turned by `sign`.
void movedOnTheHost(const Mesh& mesh, const gpu::VertexMotion& motion, float seconds, float sign,
                    std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  positions.clear();
  for (const glm::vec3& p : mesh.positions)
    positions.push_back(p + gpu::vertexMotionOffset(motion, p, seconds));
  normals.assign(positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  for (glm::vec3& n : normals)
    n = sign * glm::normalize(n);
}

std::vector<gpu::Vertex> readVertices(const VulkanContext& context, const SceneBuffers& buffers) {
  const VkDeviceSize bytes = buffers.vertices.size();
  GpuBuffer readback = hostBuffer(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  context.submitAndWait([&](VkCommandBuffer commands) {
    const VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(commands, buffers.vertices.buffer(), readback.buffer(), 1, &copy);
  });
  std::vector<gpu::Vertex> vertices(bytes / sizeof(gpu::Vertex));
  readback.read(vertices.data(), vertices.size() * sizeof(gpu::Vertex));
  return vertices;
}

TEST(VertexMotion, ThePassMovesTheNeededMeshesAsTheHostDoes) {
  testing::testOptions();
  ContextOptions options;
  options.validation = validationLayerAvailable();
  VulkanContext context(options);
  Scene scene;
  scene.meshes = {testing::quad(1.0f), cloth(8, 5, false), cloth(70, 3, true), cloth(4, 2, false)};
  for (std::uint32_t m = 0; m < scene.meshes.size(); ++m)
    scene.instances.push_back({m, 0, glm::mat4(1.0f)});
  scene.materials.push_back({});
  scene.materials[0].name = "M";
  scene.materials[0].graphText = testing::constantGraph("M", glm::vec3(0.5f), 1.0f);
  scene.animatedMeshes = {1, 2, 3};
  gpu::VertexMotion wave{}, waveAndDrift{}, drift{};
  wave.wave = glm::vec4(2.4f, 0.7f, 0.0f, 0.0f);
  waveAndDrift.wave = glm::vec4(2.4f, 2.1f, 0.0f, 0.0f);
  waveAndDrift.drift = glm::vec4(0.5f, -0.25f, 1.0f, 0.0f);
  drift.drift = glm::vec4(3.0f, 0.0f, 0.0f, 0.0f);
  scene.animatedMotions = {wave, waveAndDrift, drift};
  SceneBuffers buffers = uploadScene(context, scene);
  const std::vector<gpu::Vertex> before = readVertices(context, buffers);

  AnimatedBlases animated(context, scene, buffers, 16, {});
  // Mesh 3 is not needed this frame: it stays where it was.
  std::vector<std::uint8_t> needed = {0, 1, 1, 0};
  const float seconds = 1.7f;
  const AnimatedFrameWork work = animated.prepare(seconds, 0, needed);
  EXPECT_EQ(work.updates + work.rebuilds, 2u);
  context.submitAndWait([&](VkCommandBuffer commands) { animated.record(commands); });
  const std::vector<gpu::Vertex> after = readVertices(context, buffers);
  ASSERT_EQ(after.size(), before.size());

  float worstPosition = 0.0f, worstNormal = 0.0f, largestMove = 0.0f;
  for (std::uint32_t k = 0; k < scene.animatedMeshes.size(); ++k) {
    const std::uint32_t m = scene.animatedMeshes[k];
    const Mesh& mesh = scene.meshes[m];
    const MeshGeometry& g = buffers.geometry[m];
    std::vector<glm::vec3> positions, normals;
    movedOnTheHost(mesh, scene.animatedMotions[k], seconds, m == 2 ? -1.0f : 1.0f, positions,
                   normals);
    for (std::uint32_t v = 0; v < g.vertexCount; ++v) {
      const gpu::Vertex& was = before[g.firstVertex + v];
      const gpu::Vertex& now = after[g.firstVertex + v];
      EXPECT_EQ(now.position.w, was.position.w) << "u stays";
      EXPECT_EQ(now.normal.w, was.normal.w) << "v stays";
      EXPECT_EQ(now.tangent, was.tangent);
      EXPECT_EQ(now.color, was.color);
      if (!needed[m]) {
        EXPECT_EQ(now.position, was.position) << "mesh " << m << " was not needed";
        EXPECT_EQ(now.normal, was.normal);
        continue;
      }
      largestMove =
          std::max(largestMove, glm::distance(glm::vec3(now.position), mesh.positions[v]));
      worstPosition = std::max(worstPosition, glm::distance(glm::vec3(now.position), positions[v]));
      worstNormal = std::max(worstNormal, glm::distance(glm::vec3(now.normal), normals[v]));
    }
  }
  std::printf(
      "vertex pass against the host: positions within %g, normals within %g (moved up to "
      "%g)\n",
      worstPosition, worstNormal, largestMove);
  EXPECT_GT(largestMove, 0.5f) << "the meshes moved";
  EXPECT_LT(worstPosition, 1e-5f);
  EXPECT_LT(worstNormal, 1e-4f);
  // The static mesh's vertices are untouched.
  const MeshGeometry& still = buffers.geometry[0];
  for (std::uint32_t v = 0; v < still.vertexCount; ++v)
    EXPECT_EQ(after[still.firstVertex + v].position, before[still.firstVertex + v].position);

  // Without motions the meshes are drawn at rest: no pass is made, nothing moves.
  Scene atRest = scene;
  atRest.animatedMotions.clear();
  SceneBuffers restBuffers = uploadScene(context, atRest);
  AnimatedBlases drawnAtRest(context, atRest, restBuffers, 16, {});
  const AnimatedFrameWork none = drawnAtRest.prepare(seconds, 0, {});
  EXPECT_EQ(none.updates + none.rebuilds, 0u);
  context.submitAndWait([&](VkCommandBuffer commands) { drawnAtRest.record(commands); });
  const std::vector<gpu::Vertex> unmoved = readVertices(context, restBuffers);
  for (std::size_t v = 0; v < unmoved.size(); ++v)
    ASSERT_EQ(unmoved[v].position, before[v].position) << "vertex " << v;
  EXPECT_TRUE(context.validationErrors().empty());
}

TEST(VertexMotion, AMotionPerAnimatedMeshOrNone) {
  Scene scene;
  scene.meshes = {cloth(2, 2, false), cloth(2, 2, false)};
  scene.instances = {{0, 0, glm::mat4(1.0f)}, {1, 0, glm::mat4(1.0f)}};
  scene.materials.push_back({});
  scene.animatedMeshes = {0, 1};
  EXPECT_NO_THROW(validateScene(scene)) << "no motions: drawn at rest";
  scene.animatedMotions = {gpu::VertexMotion{}};
  try {
    validateScene(scene);
    ADD_FAILURE() << "one motion for two animated meshes was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "1 vertex motions for 2 animated meshes");
  }
  scene.animatedMotions.push_back({});
  EXPECT_NO_THROW(validateScene(scene));
  // More vertices than the pass's work groups reach (65535 of 64): refused by name.
  scene.meshes[1].positions.resize(65535u * 64u + 1u);
  try {
    validateScene(scene);
    ADD_FAILURE() << "a mesh past the vertex pass's reach was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "animated mesh 1 (mesh 1) has 4194241 vertices; at most 4194240 move");
  }
}

}  // namespace
}  // namespace memograph::runtime
