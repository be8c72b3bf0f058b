// The renderer's CPU-side scene: what an importer (assimp, built-in generators) produces and
// the runtime uploads. Plain data, no Vulkan, so that importers and tests need no device.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

// One triangle mesh; shared by every instance that references it (one BLAS per mesh).
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // per vertex, same count as positions
  std::vector<glm::vec2> uvs;          // empty: the mesh has no texture coordinates
  std::vector<glm::vec4> tangents;     // xyz tangent along +u, w handedness; may be empty
  std::vector<glm::vec4> colors;       // empty: no vertex colors
  std::vector<std::uint32_t> indices;  // three per triangle
  // Blender's texture space (Generated coordinates), when the scene says it (the Blender
  // scene export's sidecar); otherwise the object-space bounds are used.
  bool hasTextureSpace = false;
  glm::vec3 textureSpaceLocation{0.0f};
  glm::vec3 textureSpaceSize{1.0f};
};

// An axis-aligned box.
struct Bounds {
  glm::vec3 lo{0.0f};
  glm::vec3 hi{0.0f};
  glm::vec3 centre() const { return 0.5f * (lo + hi); }
};

// The box around a mesh's positions (object space); a zero box for a mesh without any.
inline Bounds meshBounds(const Mesh& mesh) {
  Bounds b;
  if (mesh.positions.empty())
    return b;
  b.lo = b.hi = mesh.positions.front();
  for (const glm::vec3& p : mesh.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

// A placed copy of a mesh with one material.
struct Instance {
  std::uint32_t mesh = 0;
  std::uint32_t material = 0;  // index into Scene::materials
  glm::mat4 objectToWorld{1.0f};
  bool castsShadow = true;  // false: a light's quad: only BSDF rays see it (as Cycles' lamps)
};

// A coarser version of a mesh (seeds/001 §3.3.1: a BLAS per mesh LOD, shared by the instances
// that show that level): its own triangles over a subset of the mesh's vertices (their
// attributes as the mesh has them), and the simplifier's object-space error, the farthest the
// simplified surface may lie from the mesh's, which the LOD choice projects to pixels.
struct MeshLod {
  Mesh mesh;
  float error = 0.0f;  // a bound on the distance from the mesh's surface, in its units
  // The longest side of the bounds of any connected part of the mesh (or of a finer level)
  // that this level removes whole, in the mesh's units: what a viewer sees vanish, which may be
  // far wider than `error` (a window's frame stands 0.2 m out but spans 1.5 m).
  float removedPart = 0.0f;
};
// LOD levels a mesh may have besides itself (the level fits the culling's byte a instance).
inline constexpr std::size_t kMaxMeshLods = 7;

// A scene material is a name that maps to a material graph (a .mgraph file, or generated
// graph text for the built-in scenes).
struct MaterialRef {
  std::string name;
  std::string graphPath;  // a .mgraph file; empty when graphText is given
  std::string graphText;  // inline graph source (built-in scenes)
  // Emissive light sampling (NEE): an estimate of the radiance the material emits, used only
  // to choose among emissive triangles by power (the emission itself is the graph's, at the
  // sampled point). Zero: the material is not sampled as a light (found by BSDF rays only).
  glm::vec3 emissionEstimate{0.0f};
  // What the estimate is. Graph: an estimate only; NEE evaluates the graph at each light
  // sample. Constant: the graph emits exactly emissionEstimate everywhere; ConstantFront: on
  // the front of each triangle (the side its winding's normal points to) and nothing
  // behind, as an area lamp. The renderer trusts a constant only for a graph that reads no
  // inputs and no textures (ConstantFront: no input but backfacing) and evaluates otherwise.
  enum class EmissionKind { Graph, Constant, ConstantFront };
  EmissionKind emissionKind = EmissionKind::Graph;
};

enum class LightType : std::uint32_t { Point = 0, Directional = 1, Spot = 2 };

struct Light {
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};                // point lights
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional lights: direction the light travels
  glm::vec3 intensity{1.0f};  // point, spot: W/sr (radiant intensity); directional: irradiance
  // Spot lights (Cycles 3.4's spot_light_attenuation): cos of half the cone angle and the
  // smoothing width in cosine, (1 - cosHalfAngle) * blend; direction is the cone's axis.
  float spotCosHalfAngle = -1.0f;
  float spotSmooth = 0.0f;
};

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float verticalFovDegrees = 45.0f;
};

// Environment: a constant radiance, or an equirectangular image (path) loaded at the edge.
struct Environment {
  glm::vec3 constantRadiance{0.0f};  // used when imageRgb is empty
  std::string imagePath;
  float imageStrength = 1.0f;    // multiplies the image when it is loaded (Blender's Strength)
  float imageUOffset = 0.0f;     // added to u when it is loaded (Blender's equirect starts at -x)
  glm::vec3 sunDirection{0.0f};  // unused unless a directional light is derived from it
  // The loaded equirectangular image (filled by the importer at the edge; the core renderer
  // reads no image files): linear RGB floats, rows top (zenith) to bottom, u = 0 at -z.
  std::vector<float> imageRgb;  // imageWidth * imageHeight * 3; empty: constant radiance
  std::uint32_t imageWidth = 0;
  std::uint32_t imageHeight = 0;
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<MaterialRef> materials;
  std::vector<Light> lights;
  Camera camera;
  Environment environment;
  bool emissiveLightSampling = true;  // NEE of emissive triangles (materials with an estimate)
  // Cycles' Filter Glossy of a Blender scene (the export's sidecar, `render filter_glossy F`):
  // glossy lobes seen after low-pdf bounces are blurred (path_shading.glsl filterGlossy); 0: off,
  // as for every scene that does not come from Blender. RendererOptions::filterGlossy
  // overrides it.
  float filterGlossy = 0.0f;
  // Meshes whose vertices move every frame (the city's flags), and how the k-th one's rest
  // vertices (object space) move (gpu::VertexMotion, vertex_motion.h): the renderer's vertex
  // pass moves them on the GPU, recomputes their normals from the moved triangles and
  // updates their BLASes in place (docs/design/culling.md). Without motions (the list empty) they
  // are drawn at rest; with them, one per animated mesh (validateScene checks).
  std::vector<std::uint32_t> animatedMeshes;
  std::vector<gpu::VertexMotion> animatedMotions;
  // Each mesh's LODs, finest first, errors increasing (empty: no mesh has any; otherwise one
  // list per mesh, empty for a mesh without LODs). Only a culled render with mesh LODs on
  // traces them (docs/design/culling.md, Mesh LODs); they never replace a mesh elsewhere.
  std::vector<std::vector<MeshLod>> meshLods;
};

}  // namespace memograph::runtime
