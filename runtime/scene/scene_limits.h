// What a scene may ask of the renderer, measured from the Scene alone (no device, no
// allocation beyond a set of graph keys) so the render's validate stage can refuse a scene
// too large for the device in milliseconds, before a shader is compiled or a buffer made.
// Every importer and built-in scene passes through it (docs/guide/limits.md).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "runtime/scene/scene.h"

namespace memograph::runtime {

// A scene (or its textures) that the renderer or the device cannot hold: not a usage error,
// so the CLI exits 1 for it (its message names the limit and the count).
class SceneLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The fixed limits, each chosen from what the runtime can hold on any device; the device's
// own limits (storage-buffer range, allocation size, heap sizes, acceleration-structure
// counts) are checked beside them in the validate stage (trace/render_setup.cpp).
//
// Materials: a scene material costs a cache record (uvec4) and an emission entry on the
// device, but its id also travels through the tile cache's sort key with the top bit taken
// (tile_cache.glsl tileSortKey: materialId & 0x7FFFFFFF); 2^20 keeps far below that and
// below what a name list of this size costs on the host (tens of MB).
inline constexpr std::uint64_t kMaxSceneMaterials = std::uint64_t(1) << 20;
// Distinct material graphs: each is compiled by the compiler library, then into a switch
// case, a callable shader or a wavefront pipeline of its own; at about 110 MB and a second
// of shader compile per graph on a CPU device (render_setup's switch limit) 4096 is already
// hours and hundreds of GB, the most any device can be asked to compile.
inline constexpr std::uint64_t kMaxSceneMaterialGraphs = 4096;
// Meshes: each is a BLAS of its own, built in one batch (acceleration_structures.cpp), with
// two device allocations (built, then compacted) and a compacted-size query each. An OBJ of
// 50 000 materials (assimp makes a mesh per material) crashed lavapipe inside the driver
// after 12 s and 1.9 GB; the city, the largest built-in scene, has about 2 300 meshes.
// 16 384 leaves room for real scenes while keeping the per-BLAS work bounded.
inline constexpr std::uint64_t kMaxSceneMeshes = 16384;
// Instances: the TLAS's instance count is bounded by the device (maxInstanceCount, at least
// 2^24); the instance buffer (224 bytes each, gpu::Instance) must fit one storage binding
// of the spec's guaranteed 128 MiB: 2^19 instances is 112 MiB.
inline constexpr std::uint64_t kMaxSceneInstances = std::uint64_t(1) << 19;
// Triangles over all meshes: 2^26 is 768 MiB of indices (12 bytes a triangle) and, at about
// one vertex per two triangles (64 bytes each, gpu::Vertex), 2 GiB of vertices, bound whole
// as storage buffers: at the edge of the largest storage range devices offer (4 GiB) and
// hours of BLAS builds on a CPU device. The full city (17.8 million) fits; devices with a
// smaller maxStorageBufferRange refuse earlier (checked beside).
inline constexpr std::uint64_t kMaxSceneTriangles = std::uint64_t(1) << 26;
// Textures: each is a mipmapped RGBA32F image in one array binding of sampled images; the
// device's maxPerStageDescriptorSampledImages bounds it too (checked beside).
inline constexpr std::uint64_t kMaxSceneTextures = 1024;
// Texels over all textures (level 0; the mip chain adds a third): RGBA32F, 16 bytes a texel,
// so 2^28 texels is 4 GiB on the host as loaded and 5.3 GiB on the device with mips.
inline constexpr std::uint64_t kMaxSceneTexels = std::uint64_t(1) << 28;

// The scene's counts and the bytes of the buffers uploadScene would make for it.
struct SceneFootprint {
  std::uint64_t materials = 0;
  std::uint64_t materialGraphs = 0;  // distinct (graph file, graph text) pairs
  std::uint64_t instances = 0;
  std::uint64_t meshes = 0;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::uint64_t largestMeshTriangles = 0;
  std::uint64_t lights = 0;
  std::uint64_t environmentTexels = 0;
  std::uint64_t vertexBytes = 0;    // gpu::Vertex per vertex
  std::uint64_t indexBytes = 0;     // uint32 per index
  std::uint64_t instanceBytes = 0;  // gpu::Instance per instance
  std::uint64_t meshBytes = 0;      // gpu::Mesh per mesh
  // The light buffer: the lights, and with emissive light sampling up to one entry per
  // triangle of every instance (an upper bound: only emitting instances add theirs).
  std::uint64_t lightBytesAtMost = 0;
  std::uint64_t environmentBytes = 0;  // vec4 per texel
};

// Counts and sizes, in one pass over the scene's arrays (no copy of them).
SceneFootprint measureScene(const Scene& scene);

// Throws SceneLimitError when a count passes its fixed limit above, naming the limit, the
// count and the scene element.
void checkSceneLimits(const SceneFootprint& footprint);

// What one scene buffer (the vertices, the indices, the instances) may take on the device the
// scene is for: the most one storage binding may address and the largest allocation. Bytes 0:
// unknown (no device yet), only the fixed limits apply.
struct SceneBufferBudget {
  std::string device;                   // the device's name, for the message
  std::uint64_t storageRangeBytes = 0;  // maxStorageBufferRange
  std::uint64_t allocationBytes = 0;    // maxMemoryAllocationSize
};

// Throws SceneLimitError when a buffer of `bytes` (`what`, e.g. "vertex buffer", made of
// `counted`, e.g. "N vertices of 64 bytes") passes the budget; `atLeast` says the count is
// of a scene still being built, so its whole buffer needs more.
void checkSceneBuffer(const SceneBufferBudget& budget, std::uint64_t bytes, const std::string& what,
                      const std::string& counted, bool storageBinding, bool atLeast = false);

// The vertex and index buffers of `vertices` and `triangles` against the budget (gpu::Vertex
// and three uint32 a triangle); `atLeast` as above. The validate stage checks the whole
// scene's counts; a built-in scene checks its counts so far after each mesh it adds
// (BuiltinSceneOptions::onGeometry), so that a scene too large for the device is refused
// before most of it is made.
void checkGeometryBuffers(const SceneBufferBudget& budget, std::uint64_t vertices,
                          std::uint64_t triangles, bool atLeast = false);

// Throws SceneLimitError when `count` textures or `texels` texels in all pass their limits.
void checkTextureLimits(std::uint64_t count, std::uint64_t texels);

}  // namespace memograph::runtime
