#include "runtime/scene/scene_limits.h"

#include <algorithm>
#include <set>
#include <string_view>
#include <utility>

#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {
namespace {

std::string count(std::uint64_t n) {
  return std::to_string(n);
}

[[noreturn]] void refuse(const std::string& what, std::uint64_t n, std::uint64_t limit,
                         const std::string& why) {
  throw SceneLimitError("the scene has " + count(n) + " " + what + ", more than the limit of " +
                        count(limit) + " (" + why + ")");
}

}  // namespace

SceneFootprint measureScene(const Scene& scene) {
  SceneFootprint f;
  f.materials = scene.materials.size();
  // Views into the scene's strings: the set costs a pointer pair per distinct graph.
  std::set<std::pair<std::string_view, std::string_view>> graphs;
  for (const MaterialRef& m : scene.materials)
    graphs.emplace(m.graphPath, m.graphText);
  f.materialGraphs = graphs.size();
  f.instances = scene.instances.size();
  f.meshes = scene.meshes.size();
  for (const Mesh& mesh : scene.meshes) {
    f.vertices += mesh.positions.size();
    const std::uint64_t triangles = mesh.indices.size() / 3;
    f.triangles += triangles;
    f.largestMeshTriangles = std::max(f.largestMeshTriangles, triangles);
  }
  f.lights = scene.lights.size();
  std::uint64_t emissiveTriangles = 0;
  if (scene.emissiveLightSampling) {
    for (const Instance& instance : scene.instances) {
      if (instance.material >= scene.materials.size() || instance.mesh >= scene.meshes.size())
        continue;  // validateScene reports it
      const glm::vec3 e = scene.materials[instance.material].emissionEstimate;
      if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f)
        emissiveTriangles += scene.meshes[instance.mesh].indices.size() / 3;
    }
  }
  f.environmentTexels = std::uint64_t(scene.environment.imageWidth) * scene.environment.imageHeight;
  f.vertexBytes = f.vertices * sizeof(gpu::Vertex);
  f.indexBytes = f.triangles * 3 * sizeof(std::uint32_t);
  f.instanceBytes = f.instances * sizeof(gpu::Instance);
  f.meshBytes = f.meshes * sizeof(gpu::Mesh);
  f.lightBytesAtMost = (f.lights + emissiveTriangles) * sizeof(gpu::Light);
  f.environmentBytes = f.environmentTexels * sizeof(glm::vec4);
  return f;
}

void checkSceneLimits(const SceneFootprint& f) {
  if (f.materials > kMaxSceneMaterials)
    refuse("materials", f.materials, kMaxSceneMaterials,
           "each material's id and cache record live on the device");
  if (f.materialGraphs > kMaxSceneMaterialGraphs)
    refuse("distinct material graphs", f.materialGraphs, kMaxSceneMaterialGraphs,
           "each graph is compiled into the path tracer's shaders");
  if (f.meshes > kMaxSceneMeshes)
    refuse("meshes", f.meshes, kMaxSceneMeshes,
           "each mesh is an acceleration structure of its own; an OBJ gets one mesh per "
           "material ('usemtl') of each object");
  if (f.instances > kMaxSceneInstances)
    refuse("instances", f.instances, kMaxSceneInstances,
           "the instance buffer is one storage binding");
  if (f.triangles > kMaxSceneTriangles)
    refuse("triangles", f.triangles, kMaxSceneTriangles,
           "the vertex and index buffers are storage bindings");
}

void checkSceneBuffer(const SceneBufferBudget& budget, std::uint64_t bytes, const std::string& what,
                      const std::string& counted, bool storageBinding, bool atLeast) {
  const std::string need = "the scene's " + what + " would need " + (atLeast ? "at least " : "") +
                           count(bytes) + " bytes (" + counted + ")";
  const std::uint64_t range = budget.storageRangeBytes;
  if (storageBinding && range > 0 && bytes > range)
    throw SceneLimitError(need + ", more than the " + count(range) +
                          "-byte storage-buffer range of " + budget.device +
                          " (maxStorageBufferRange, the most one binding may address)");
  if (budget.allocationBytes > 0 && bytes > budget.allocationBytes)
    throw SceneLimitError(need + ", more than the largest allocation of " + budget.device + " (" +
                          count(budget.allocationBytes) + " bytes)");
}

void checkGeometryBuffers(const SceneBufferBudget& budget, std::uint64_t vertices,
                          std::uint64_t triangles, bool atLeast) {
  const std::string soFar = atLeast ? " so far" : "";
  checkSceneBuffer(
      budget, vertices * sizeof(gpu::Vertex), "vertex buffer",
      count(vertices) + " vertices of " + count(sizeof(gpu::Vertex)) + " bytes" + soFar, true,
      atLeast);
  checkSceneBuffer(
      budget, triangles * 3 * sizeof(std::uint32_t), "index buffer",
      count(triangles) + " triangles of " + count(3 * sizeof(std::uint32_t)) + " bytes" + soFar,
      true, atLeast);
}

void checkTextureLimits(std::uint64_t textures, std::uint64_t texels) {
  if (textures > kMaxSceneTextures)
    refuse("textures", textures, kMaxSceneTextures,
           "each is an image in the path tracer's texture array");
  if (texels > kMaxSceneTexels)
    refuse("texels in its textures", texels, kMaxSceneTexels,
           "RGBA32F, 16 bytes a texel before mip levels, held on the host and the device");
}

}  // namespace memograph::runtime
