#include "runtime/scene/builtin/mesh_lods.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include <meshoptimizer.h>

#include "runtime/host/parallel_for.h"

namespace memograph::runtime {
namespace {

struct SimplifiedMesh {
  Mesh mesh;
  float error = 0.0f;        // this pass's, in the mesh's units
  float removedPart = 0.0f;  // the longest side of a part it removed whole (MeshLod)
};

// The longest side of the bounds of any connected part of the welded mesh (`indices` over
// `positions`) of which `kept` (the simplified indices) holds no triangle. The simplifier
// bounds how far the surface moves, which for a part it collapses whole is its thickness; but
// what a viewer sees go is its width and length (seeds/001 §3.1.1: the LOD must keep what is
// seen).
float longestRemovedPart(const std::vector<glm::vec3>& positions,
                         const std::vector<unsigned int>& indices,
                         const std::vector<unsigned int>& kept) {
  std::vector<std::uint32_t> part(positions.size());
  for (std::uint32_t v = 0; v < part.size(); ++v)
    part[v] = v;
  const auto root = [&](std::uint32_t v) {
    while (part[v] != v)
      v = part[v] = part[part[v]];
    return v;
  };
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    for (int k = 1; k < 3; ++k)
      part[root(indices[t + k])] = root(indices[t]);
  std::vector<std::uint8_t> survives(positions.size(), 0);
  for (const unsigned int v : kept)
    survives[root(v)] = 1;
  std::vector<glm::vec3> lo(positions.size(), glm::vec3(std::numeric_limits<float>::max()));
  std::vector<glm::vec3> hi(positions.size(), glm::vec3(std::numeric_limits<float>::lowest()));
  for (const unsigned int v : indices) {
    const std::uint32_t r = root(v);
    lo[r] = glm::min(lo[r], positions[v]);
    hi[r] = glm::max(hi[r], positions[v]);
  }
  float longest = 0.0f;
  for (std::uint32_t r = 0; r < positions.size(); ++r)
    if (part[r] == r && !survives[r] && hi[r].x >= lo[r].x) {
      const glm::vec3 side = hi[r] - lo[r];
      longest = std::max({longest, side.x, side.y, side.z});
    }
  return longest;
}

// One pass of the simplifier over `source` within `targetError` (the mesh's units).
SimplifiedMesh simplifyOnce(const Mesh& source, float targetError) {
  const std::size_t vertexCount = source.positions.size();
  // Weld by position: a box's faces are split for their normals, and the simplifier only
  // collapses along edges it sees shared.
  std::vector<unsigned int> weld(vertexCount);
  const std::size_t weldedCount = meshopt_generateVertexRemap(
      weld.data(), nullptr, vertexCount, source.positions.data(), vertexCount, sizeof(glm::vec3));
  std::vector<glm::vec3> weldedPositions(weldedCount);
  // Each welded vertex's source vertices, lowest index first (the attributes to choose from).
  std::vector<std::vector<std::uint32_t>> sources(weldedCount);
  for (std::uint32_t v = 0; v < vertexCount; ++v) {
    weldedPositions[weld[v]] = source.positions[v];
    sources[weld[v]].push_back(v);
  }
  std::vector<unsigned int> weldedIndices(source.indices.size());
  for (std::size_t k = 0; k < source.indices.size(); ++k)
    weldedIndices[k] = weld[source.indices[k]];

  SimplifiedMesh out;
  const float scale = meshopt_simplifyScale(&weldedPositions[0].x, weldedCount, sizeof(glm::vec3));
  if (!(scale > 0.0f) || !(targetError > 0.0f))
    return out;
  std::vector<unsigned int> simplified(weldedIndices.size());
  float relativeError = 0.0f;
  // Target 0 triangles: the error bound alone stops it.
  const std::size_t indexCount = meshopt_simplify(
      simplified.data(), weldedIndices.data(), weldedIndices.size(), &weldedPositions[0].x,
      weldedCount, sizeof(glm::vec3), 0, targetError / scale, 0, &relativeError);
  simplified.resize(indexCount);
  out.error = relativeError * scale;
  out.removedPart = longestRemovedPart(weldedPositions, weldedIndices, simplified);

  // Each corner takes the source vertex at its position whose normal is nearest the
  // triangle's own (the first of equals): a flat face keeps its normal and uvs.
  std::vector<std::uint32_t> newIndex(vertexCount, std::numeric_limits<std::uint32_t>::max());
  Mesh& mesh = out.mesh;
  mesh.name = source.name;
  mesh.hasTextureSpace = source.hasTextureSpace;
  mesh.textureSpaceLocation = source.textureSpaceLocation;
  mesh.textureSpaceSize = source.textureSpaceSize;
  for (std::size_t t = 0; t + 2 < simplified.size(); t += 3) {
    const glm::vec3 a = weldedPositions[simplified[t]], b = weldedPositions[simplified[t + 1]],
                    c = weldedPositions[simplified[t + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) {
      const std::vector<std::uint32_t>& candidates = sources[simplified[t + k]];
      std::uint32_t best = candidates.front();
      float bestDot = -std::numeric_limits<float>::infinity();
      for (const std::uint32_t v : candidates) {
        const float d = glm::dot(source.normals[v], face);
        if (d > bestDot) {
          bestDot = d;
          best = v;
        }
      }
      if (newIndex[best] == std::numeric_limits<std::uint32_t>::max()) {
        newIndex[best] = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.push_back(source.positions[best]);
        mesh.normals.push_back(source.normals[best]);
        if (!source.uvs.empty())
          mesh.uvs.push_back(source.uvs[best]);
        if (!source.tangents.empty())
          mesh.tangents.push_back(source.tangents[best]);
        if (!source.colors.empty())
          mesh.colors.push_back(source.colors[best]);
      }
      mesh.indices.push_back(newIndex[best]);
    }
  }
  return out;
}

}  // namespace

std::vector<MeshLod> buildMeshLods(const Mesh& mesh, const MeshLodSettings& settings) {
  std::vector<MeshLod> lods;
  lods.reserve(settings.relativeErrors.size());
  const std::size_t triangles = mesh.indices.size() / 3;
  // A mesh the upload would refuse gets none (validateScene names its problem).
  if (triangles < settings.minTriangles || mesh.normals.size() != mesh.positions.size() ||
      mesh.indices.size() % 3 != 0)
    return lods;
  for (const std::uint32_t index : mesh.indices)
    if (index >= mesh.positions.size())
      return lods;
  const float extent =
      meshopt_simplifyScale(&mesh.positions[0].x, mesh.positions.size(), sizeof(glm::vec3));
  const Mesh* finer = &mesh;
  float finerError = 0.0f;
  for (const float relative : settings.relativeErrors) {
    if (lods.size() >= kMaxMeshLods)
      break;
    // What this level's target leaves to its pass after the passes before it.
    const float budget = relative * extent - finerError;
    if (!(budget > 0.0f))
      continue;
    SimplifiedMesh pass = simplifyOnce(*finer, budget);
    const std::size_t kept = pass.mesh.indices.size() / 3;
    const std::size_t finerTriangles = finer->indices.size() / 3;
    if (kept == 0)
      break;
    // Too little gone within this target: skipped, and the next, wider target tried from the
    // same finer mesh (a building whose frames are plain boxes loses only a tenth of its
    // triangles within 0.25 % of its extent, but three quarters within 0.75 %).
    if (double(kept) > settings.maxTriangleFraction * double(finerTriangles))
      continue;
    const float removedPart =
        lods.empty() ? pass.removedPart : std::max(lods.back().removedPart, pass.removedPart);
    lods.push_back({std::move(pass.mesh), finerError + pass.error, removedPart});
    finer = &lods.back().mesh;
    finerError = lods.back().error;
  }
  return lods;
}

void addMeshLods(Scene& scene, const std::vector<std::uint32_t>& listed,
                 const MeshLodSettings& settings) {
  // Each mesh once, so that no two threads write one mesh's LODs.
  std::vector<std::uint32_t> meshes = listed;
  std::sort(meshes.begin(), meshes.end());
  meshes.erase(std::unique(meshes.begin(), meshes.end()), meshes.end());
  for (const std::uint32_t m : meshes)
    if (m >= scene.meshes.size())
      throw std::invalid_argument("addMeshLods: mesh " + std::to_string(m) + " of " +
                                  std::to_string(scene.meshes.size()));
  scene.meshLods.resize(scene.meshes.size());
  // The meshes are independent, each simplified alone, so threads give the same LODs as one
  // thread: the full city's 2,000 buildings took 6 s of one core.
  parallelFor(meshes.size(), 0, [&](std::size_t k, std::uint32_t) {
    scene.meshLods[meshes[k]] = buildMeshLods(scene.meshes[meshes[k]], settings);
  });
}

}  // namespace memograph::runtime
