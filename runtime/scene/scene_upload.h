// Uploads a runtime::Scene into the GPU buffers the path tracer reads (shared_types.h
// layouts), after checking it: every index, mesh and material reference in range, so a bad
// scene gets a message naming the element instead of a device fault.
#pragma once

#include <vector>

#include "runtime/accel/acceleration_structures.h"
#include "runtime/scene/scene.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

// Throws std::invalid_argument naming the first problem.
void validateScene(const Scene& scene);

struct SceneBuffers {
  GpuBuffer vertices;     // gpu::Vertex
  GpuBuffer indices;      // uint32, relative to each mesh's first vertex
  GpuBuffer meshes;       // gpu::Mesh
  GpuBuffer instances;    // gpu::Instance
  GpuBuffer lights;       // gpu::Light
  GpuBuffer environment;  // vec4 texels of the environment image (one texel if none)
  std::vector<MeshGeometry> geometry;
  // The LOD meshes (Scene::meshLods) follow the scene's meshes in the vertex, index and mesh
  // buffers, level-major (every mesh's first LOD, then every second one, ...): lodGeometry[k]
  // is gpu::Mesh geometry.size() + k. The BLAS cache takes geometry then lodGeometry as its
  // meshes and builds the lowest index first, so under a build budget finer levels come first.
  // meshLodIds[mesh][l]: that index of the mesh's LOD l + 1 (empty without LODs).
  std::vector<MeshGeometry> lodGeometry;
  std::vector<std::vector<std::uint32_t>> meshLodIds;
  std::vector<InstancePlacement> placements;
  std::uint32_t lightCount = 0;
  std::uint32_t environmentWidth = 0;  // 0: constant environment
  std::uint32_t environmentHeight = 0;
  // The light buffer ends with emissive triangles for NEE: the path tracer needs
  // MG_EMISSIVE_NEE (without it, no kernel carries their sampling and MIS).
  bool emissiveTriangles = false;
};

struct LinkedMaterials;

// Each scene material's declared MaterialRef::EmissionKind where its compiled graph bears
// it out (Constant: reads no input and no texture; ConstantFront: none but backfacing),
// else Graph: a declared constant is never trusted for a graph that could vary.
std::vector<MaterialRef::EmissionKind> emissionKindsVerified(const Scene& scene,
                                                             const LinkedMaterials& linked);

// Whether some emitter's material must be evaluated at NEE's light samples (its emission is
// not a known constant), so the path tracer needs MG_NEE_EVALUATES_EMISSION: light sampling
// on and an emitting instance with triangles whose kind is Graph. Known before the upload,
// so that --shading auto can choose by it; an emitter of only degenerate triangles (none
// sampled) counts too, which only compiles an unused call site.
bool sceneNeeEvaluatesEmission(const Scene& scene,
                               const std::vector<MaterialRef::EmissionKind>& emissionKinds);

// Per scene material, whether NEE evaluates it at some emitter's light samples (the
// instances sceneNeeEvaluatesEmission looks for, by their material): the wavefront compiles
// the evaluation of light points only into those materials' graphs' passes.
std::vector<bool> neeEvaluatedMaterials(
    const Scene& scene, const std::vector<MaterialRef::EmissionKind>& emissionKinds);

// `emissionKinds`: per scene material, the emission NEE may take as known (see
// MaterialRef::EmissionKind and emissionKindsVerified); empty: every material Graph.
SceneBuffers uploadScene(const VulkanContext& context, const Scene& scene,
                         const std::vector<MaterialRef::EmissionKind>& emissionKinds = {});

// Blender's automatic texture space of a mesh (BKE_mesh_texspace_calc), which Generated
// coordinates map to [0, 1]^3: the centre of the object-space bounding box and half its
// extent, a zero half extent replaced by 1 and one below 1e-5 raised to 1e-5. An empty
// mesh gets location 0, size 1.
struct TextureSpace {
  glm::vec3 location{0.0f};
  glm::vec3 size{1.0f};
};
TextureSpace autoTextureSpace(const Mesh& mesh);
// Each scene mesh's texture space as the upload writes it: the mesh's own where it has one
// (Mesh::hasTextureSpace), else Blender's automatic one.
std::vector<TextureSpace> sceneTextureSpaces(const Scene& scene);

}  // namespace memograph::runtime
