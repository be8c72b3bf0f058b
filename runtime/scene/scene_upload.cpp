#include "runtime/scene/scene_upload.h"

#include <cmath>
#include <stdexcept>

#include <glm/gtc/constants.hpp>
#include <string>

#include "runtime/materials/material_linker.h"
#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
constexpr VkBufferUsageFlags kGeometry =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT;  // read back by tests

constexpr std::uint64_t kMaxWorkGroups = 65535;

std::string meshLabel(const Mesh& mesh, std::size_t index) {
  return "mesh " + std::to_string(index) + (mesh.name.empty() ? "" : " ('" + mesh.name + "')");
}

}  // namespace

void validateScene(const Scene& scene) {
  if (scene.meshes.empty())
    throw std::invalid_argument("the scene has no meshes");
  if (scene.instances.empty())
    throw std::invalid_argument("the scene has no instances");
  if (!scene.animatedMotions.empty() && scene.animatedMotions.size() != scene.animatedMeshes.size())
    throw std::invalid_argument(std::to_string(scene.animatedMotions.size()) +
                                " vertex motions for " +
                                std::to_string(scene.animatedMeshes.size()) + " animated meshes");
  // The vertex pass (vertex_motion.comp) dispatches a work group row per animated mesh and
  // a work group per kVertexMotionWorkgroup vertices, each within the group count every
  // device has (maxComputeWorkGroupCount is at least 65535).
  if (scene.animatedMeshes.size() > kMaxWorkGroups)
    throw std::invalid_argument("the scene has " + std::to_string(scene.animatedMeshes.size()) +
                                " animated meshes; at most " + std::to_string(kMaxWorkGroups) +
                                " move");
  std::vector<bool> animated(scene.meshes.size(), false);
  for (std::size_t k = 0; k < scene.animatedMeshes.size(); ++k) {
    const std::uint32_t mesh = scene.animatedMeshes[k];
    if (mesh >= scene.meshes.size())
      throw std::invalid_argument("animated mesh " + std::to_string(k) + " names mesh " +
                                  std::to_string(mesh) + ", but the scene has " +
                                  std::to_string(scene.meshes.size()) + " meshes");
    if (animated[mesh])
      throw std::invalid_argument("mesh " + std::to_string(mesh) + " is listed twice as animated");
    if (scene.meshes[mesh].positions.size() > kMaxWorkGroups * gpu::kVertexMotionWorkgroup)
      throw std::invalid_argument(
          "animated mesh " + std::to_string(k) + " (" + meshLabel(scene.meshes[mesh], mesh) +
          ") has " + std::to_string(scene.meshes[mesh].positions.size()) + " vertices; at most " +
          std::to_string(kMaxWorkGroups * gpu::kVertexMotionWorkgroup) + " move");
    animated[mesh] = true;
  }
  const auto checkMesh = [](const Mesh& mesh, const std::string& label) {
    if (mesh.positions.empty() || mesh.indices.empty())
      throw std::invalid_argument(label + " has no triangles");
    if (mesh.indices.size() % 3 != 0)
      throw std::invalid_argument(label + ": index count " + std::to_string(mesh.indices.size()) +
                                  " is not a multiple of 3");
    if (mesh.normals.size() != mesh.positions.size())
      throw std::invalid_argument(label + ": " + std::to_string(mesh.normals.size()) +
                                  " normals for " + std::to_string(mesh.positions.size()) +
                                  " positions");
    auto checkOptional = [&](std::size_t count, const char* what) {
      if (count != 0 && count != mesh.positions.size())
        throw std::invalid_argument(label + ": " + std::to_string(count) + " " + what + " for " +
                                    std::to_string(mesh.positions.size()) + " positions");
    };
    checkOptional(mesh.uvs.size(), "uvs");
    checkOptional(mesh.tangents.size(), "tangents");
    checkOptional(mesh.colors.size(), "colors");
    for (std::size_t k = 0; k < mesh.indices.size(); ++k) {
      if (mesh.indices[k] >= mesh.positions.size())
        throw std::invalid_argument(label + ": index " + std::to_string(k) + " is " +
                                    std::to_string(mesh.indices[k]) + ", past its " +
                                    std::to_string(mesh.positions.size()) + " vertices");
    }
  };
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    checkMesh(scene.meshes[i], meshLabel(scene.meshes[i], i));
  // LODs (Scene::meshLods): one list per mesh, each level a valid mesh whose error does not
  // fall below the finer level's; an animated mesh has none (its BLAS is updated in place).
  if (!scene.meshLods.empty() && scene.meshLods.size() != scene.meshes.size())
    throw std::invalid_argument(std::to_string(scene.meshLods.size()) + " mesh LOD lists for " +
                                std::to_string(scene.meshes.size()) + " meshes");
  for (std::size_t i = 0; i < scene.meshLods.size(); ++i) {
    if (scene.meshLods[i].empty())
      continue;
    const std::string label = meshLabel(scene.meshes[i], i);
    if (animated[i])
      throw std::invalid_argument(label + " is animated and has LODs");
    if (scene.meshLods[i].size() > kMaxMeshLods)
      throw std::invalid_argument(label + " has " + std::to_string(scene.meshLods[i].size()) +
                                  " LODs; at most " + std::to_string(kMaxMeshLods));
    float previous = 0.0f;
    for (std::size_t l = 0; l < scene.meshLods[i].size(); ++l) {
      const MeshLod& lod = scene.meshLods[i][l];
      const std::string lodLabel = label + " LOD " + std::to_string(l + 1);
      checkMesh(lod.mesh, lodLabel);
      if (!(lod.error >= previous) || !std::isfinite(lod.error))
        throw std::invalid_argument(lodLabel + ": error " + std::to_string(lod.error) +
                                    " is below the finer level's or not finite");
      previous = lod.error;
    }
  }
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    if (instance.mesh >= scene.meshes.size())
      throw std::invalid_argument("instance " + std::to_string(i) + " names mesh " +
                                  std::to_string(instance.mesh) + " of " +
                                  std::to_string(scene.meshes.size()));
    if (instance.material >= scene.materials.size())
      throw std::invalid_argument("instance " + std::to_string(i) + " names material " +
                                  std::to_string(instance.material) + " of " +
                                  std::to_string(scene.materials.size()));
  }
  const Environment& env = scene.environment;
  if (!env.imageRgb.empty() &&
      env.imageRgb.size() != std::size_t(env.imageWidth) * env.imageHeight * 3)
    throw std::invalid_argument("environment image: " + std::to_string(env.imageRgb.size()) +
                                " floats for " + std::to_string(env.imageWidth) + "x" +
                                std::to_string(env.imageHeight) + " RGB texels");
  if (env.imageRgb.empty() && !env.imagePath.empty())
    throw std::invalid_argument("environment image '" + env.imagePath +
                                "' was named but not loaded (the importer fills imageRgb)");
}

TextureSpace autoTextureSpace(const Mesh& mesh) {
  TextureSpace space;
  if (mesh.positions.empty())
    return space;
  const Bounds bounds = meshBounds(mesh);
  space.location = bounds.centre();
  space.size = 0.5f * (bounds.hi - bounds.lo);
  for (int k = 0; k < 3; ++k) {
    if (space.size[k] == 0.0f)
      space.size[k] = 1.0f;
    else if (space.size[k] < 1e-5f)
      space.size[k] = 1e-5f;
  }
  return space;
}

std::vector<TextureSpace> sceneTextureSpaces(const Scene& scene) {
  std::vector<TextureSpace> spaces;
  spaces.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) {
    if (!mesh.hasTextureSpace) {
      spaces.push_back(autoTextureSpace(mesh));  // a pass over its vertices
      continue;
    }
    TextureSpace space{mesh.textureSpaceLocation, mesh.textureSpaceSize};
    for (int k = 0; k < 3; ++k)
      if (space.size[k] == 0.0f)
        space.size[k] = 1.0f;
    spaces.push_back(space);
  }
  return spaces;
}

std::vector<MaterialRef::EmissionKind> emissionKindsVerified(const Scene& scene,
                                                             const LinkedMaterials& linked) {
  std::vector<MaterialRef::EmissionKind> kinds;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    auto kind = scene.materials[i].emissionKind;
    if (kind != MaterialRef::EmissionKind::Graph) {
      const LinkedMaterial* m = i < linked.materials.size() ? &linked.materials[i] : nullptr;
      // An opacity below 1 scales what NEE takes from an emitter (Cycles' expanded Principled
      // weighs its emission by Alpha), so its graph is evaluated at the light sample.
      bool constant = m && m->textureCount == 0 && !m->stochasticOpacity;
      if (constant)
        for (const std::string& input : m->inputsUsed)
          if (!(kind == MaterialRef::EmissionKind::ConstantFront && input == "backfacing"))
            constant = false;
      if (!constant)
        kind = MaterialRef::EmissionKind::Graph;
    }
    kinds.push_back(kind);
  }
  return kinds;
}

// The luminance of an instance's emission estimate (the light power NEE samples by).
static float emissionLuminance(const Scene& scene, const Instance& instance) {
  const glm::vec3 e = scene.materials[instance.material].emissionEstimate;
  return 0.2126f * e.r + 0.7152f * e.g + 0.0722f * e.b;
}

// An instance whose light samples NEE evaluates its material at: light sampling on, an
// emitting instance with triangles, its material's emission kind Graph (as uploadScene's
// emissive triangles with w = 0).
static bool neeEvaluatesInstance(const Scene& scene, const Instance& instance,
                                 const std::vector<MaterialRef::EmissionKind>& emissionKinds) {
  const bool graph = instance.material >= emissionKinds.size() ||
                     emissionKinds[instance.material] == MaterialRef::EmissionKind::Graph;
  return scene.emissiveLightSampling && graph && emissionLuminance(scene, instance) > 0.0f &&
         scene.meshes[instance.mesh].indices.size() >= 3;
}

bool sceneNeeEvaluatesEmission(const Scene& scene,
                               const std::vector<MaterialRef::EmissionKind>& emissionKinds) {
  for (const Instance& instance : scene.instances)
    if (neeEvaluatesInstance(scene, instance, emissionKinds))
      return true;
  return false;
}

std::vector<bool> neeEvaluatedMaterials(
    const Scene& scene, const std::vector<MaterialRef::EmissionKind>& emissionKinds) {
  std::vector<bool> evaluated(scene.materials.size(), false);
  for (const Instance& instance : scene.instances)
    if (instance.material < evaluated.size() &&
        neeEvaluatesInstance(scene, instance, emissionKinds))
      evaluated[instance.material] = true;
  return evaluated;
}

SceneBuffers uploadScene(const VulkanContext& context, const Scene& scene,
                         const std::vector<MaterialRef::EmissionKind>& emissionKinds) {
  validateScene(scene);
  SceneBuffers out;
  std::vector<gpu::Vertex> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<gpu::Mesh> meshes;
  // A mesh's ranges in the buffers; `space`: its texture space (a LOD keeps its mesh's, so
  // that Generated coordinates do not move when the level changes).
  const auto append = [&](const Mesh& mesh, const TextureSpace& space) {
    MeshGeometry g;
    g.firstVertex = static_cast<std::uint32_t>(vertices.size());
    g.vertexCount = static_cast<std::uint32_t>(mesh.positions.size());
    g.firstIndex = static_cast<std::uint32_t>(indices.size());
    g.triangleCount = static_cast<std::uint32_t>(mesh.indices.size() / 3);
    std::uint32_t flags = (mesh.uvs.empty() ? 0 : gpu::kMeshHasUvs) |
                          (mesh.tangents.empty() ? 0 : gpu::kMeshHasTangents) |
                          (mesh.colors.empty() ? 0 : gpu::kMeshHasColors);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
      gpu::Vertex vertex;
      vertex.position = glm::vec4(mesh.positions[v], uv.x);
      vertex.normal = glm::vec4(mesh.normals[v], uv.y);
      vertex.tangent = mesh.tangents.empty() ? glm::vec4(0.0f) : mesh.tangents[v];
      vertex.color = mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[v];
      vertices.push_back(vertex);
    }
    indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    gpu::Mesh gm;
    gm.ranges = glm::uvec4(g.firstVertex, g.firstIndex, flags, g.triangleCount);
    gm.textureSpaceLocation = glm::vec4(space.location, 0.0f);
    gm.textureSpaceSize = glm::vec4(space.size, 0.0f);
    meshes.push_back(gm);
    return g;
  };
  const std::vector<TextureSpace> spaces = sceneTextureSpaces(scene);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    out.geometry.push_back(append(scene.meshes[m], spaces[m]));
  if (!scene.meshLods.empty()) {
    out.meshLodIds.resize(scene.meshes.size());
    for (std::size_t level = 0; level < kMaxMeshLods; ++level)
      for (std::size_t m = 0; m < scene.meshLods.size(); ++m) {
        if (level >= scene.meshLods[m].size())
          continue;
        out.meshLodIds[m].push_back(
            static_cast<std::uint32_t>(out.geometry.size() + out.lodGeometry.size()));
        out.lodGeometry.push_back(append(scene.meshLods[m][level].mesh, spaces[m]));
      }
  }
  std::vector<gpu::Instance> instances;
  for (const Instance& instance : scene.instances) {
    gpu::Instance gi;
    gi.objectToWorld = instance.objectToWorld;
    gi.worldToObject = glm::inverse(instance.objectToWorld);
    gi.normalToWorld = glm::transpose(gi.worldToObject);
    // z: the mesh whose triangles the TLAS holds for it, its own until a culled render
    // picks one of its LODs (DynamicAccelerationStructures writes z then).
    gi.ids = glm::uvec4(instance.mesh, instance.material, instance.mesh, 0);
    // Object Info's Random: 24 bits of a PCG hash of the instance index (Blender hashes
    // the object's name; the index is what a memograph scene has).
    const auto index = static_cast<std::uint32_t>(instances.size());
    gi.objectInfo =
        glm::vec4(float(pcgHash(index ^ 0x5bd1e995u) >> 8) * (1.0f / 16777216.0f), 0, 0, 0);
    instances.push_back(gi);
    out.placements.push_back({instance.mesh, instance.objectToWorld, instance.castsShadow});
  }
  std::vector<gpu::Light> lights;
  for (const Light& light : scene.lights) {
    gpu::Light gl;
    bool point = light.type != LightType::Directional;
    const std::uint32_t type = light.type == LightType::Point  ? gpu::kLightPoint
                               : light.type == LightType::Spot ? gpu::kLightSpot
                                                               : gpu::kLightDirectional;
    gl.positionOrDirection = glm::vec4(point ? light.position : light.direction, float(type));
    gl.intensity = glm::vec4(light.intensity, 0.0f);
    const glm::vec3 axis = glm::length(light.direction) > 0.0f ? glm::normalize(light.direction)
                                                               : glm::vec3(0.0f, -1.0f, 0.0f);
    gl.spot = glm::vec4(axis, light.spotCosHalfAngle);
    gl.spotSmooth = glm::vec4(light.spotSmooth, 0.0f, 0.0f, 0.0f);
    lights.push_back(gl);
  }
  // Emissive triangles (NEE), sampled by power: world area x pi x luminance of the material's
  // emission estimate. With punctual lights too, half the samples go to each group, so the
  // area pdf of a point on instance i is pGroup * pi * lum(material) / total power.
  std::vector<gpu::Light> triangles;
  std::vector<double> power;
  double totalPower = 0.0;
  if (scene.emissiveLightSampling) {
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
      const Instance& instance = scene.instances[i];
      const float lum = emissionLuminance(scene, instance);
      if (!(lum > 0.0f))
        continue;
      // The emission NEE takes as it is (w: 1 both sides, 2 front only), or w = 0: the
      // shader evaluates the material at the sample.
      const auto kind = instance.material < emissionKinds.size() ? emissionKinds[instance.material]
                                                                 : MaterialRef::EmissionKind::Graph;
      const glm::vec4 emission =
          kind == MaterialRef::EmissionKind::Graph
              ? glm::vec4(0.0f)
              : glm::vec4(scene.materials[instance.material].emissionEstimate,
                          kind == MaterialRef::EmissionKind::Constant ? 1.0f : 2.0f);
      const Mesh& mesh = scene.meshes[instance.mesh];
      for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::vec3 p[3];
        for (int k = 0; k < 3; ++k)
          p[k] = glm::vec3(instance.objectToWorld *
                           glm::vec4(mesh.positions[mesh.indices[t + k]], 1.0f));
        const float area = 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
        if (!(area > 0.0f))
          continue;
        gpu::Light gl;
        gl.positionOrDirection = glm::vec4(0.0f, 0.0f, 0.0f, float(gpu::kLightTriangle));
        gl.spot = glm::vec4(glm::uintBitsToFloat(std::uint32_t(i)),
                            glm::uintBitsToFloat(std::uint32_t(t / 3)), area, 0.0f);
        gl.spotSmooth = emission;
        triangles.push_back(gl);
        power.push_back(double(area) * glm::pi<double>() * lum);
        totalPower += power.back();
      }
    }
  }
  out.emissiveTriangles = !triangles.empty();
  if (!triangles.empty()) {
    const double pGroup = lights.empty() ? 1.0 : 0.5;
    double cdf = 0.0;
    for (std::size_t k = 0; k < triangles.size(); ++k) {
      cdf += power[k] / totalPower;
      triangles[k].intensity = glm::vec4(k + 1 == triangles.size() ? 1.0f : float(cdf),
                                         float(lights.size()), float(triangles.size()), 0.0f);
    }
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
      const float lum = emissionLuminance(scene, scene.instances[i]);
      if (lum > 0.0f)
        instances[i].objectInfo.y = float(pGroup * glm::pi<double>() * lum / totalPower);
    }
    lights.insert(lights.end(), triangles.begin(), triangles.end());
  }
  std::vector<glm::vec4> environment(1, glm::vec4(0.0f));
  const Environment& env = scene.environment;
  if (!env.imageRgb.empty()) {
    environment.resize(std::size_t(env.imageWidth) * env.imageHeight);
    for (std::size_t i = 0; i < environment.size(); ++i)
      environment[i] =
          glm::vec4(env.imageRgb[3 * i], env.imageRgb[3 * i + 1], env.imageRgb[3 * i + 2], 1.0f);
    out.environmentWidth = env.imageWidth;
    out.environmentHeight = env.imageHeight;
  }

  out.vertices = uploadBuffer<gpu::Vertex>(context, vertices, kGeometry);
  out.indices = uploadBuffer<std::uint32_t>(context, indices, kGeometry);
  out.meshes = uploadBuffer<gpu::Mesh>(context, meshes, kStorage);
  // A culled render with mesh LODs copies each instance's LOD mesh into ids.z.
  out.instances =
      uploadBuffer<gpu::Instance>(context, instances, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  out.lights = uploadBuffer<gpu::Light>(context, lights, kStorage);
  out.environment = uploadBuffer<glm::vec4>(context, environment, kStorage);
  out.lightCount = static_cast<std::uint32_t>(lights.size());
  return out;
}

}  // namespace memograph::runtime
