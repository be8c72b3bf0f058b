#include "runtime/scene/builtin/scene_validation.h"

#include <cmath>

#include "runtime/scene/camera_range.h"

namespace memograph::runtime {
namespace {

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r]))
        return false;
    }
  }
  return true;
}

}  // namespace

bool validateScene(const Scene& scene, const std::string& sceneName,
                   compiler::Diagnostics& diagnostics) {
  const std::size_t errorsBefore = diagnostics.errorCount();
  const auto error = [&](const std::string& message) { diagnostics.error(sceneName, message); };
  if (scene.instances.empty())
    error("the scene has no instances: nothing to render");
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const std::string what = "mesh " + std::to_string(m) + " ('" + mesh.name + "')";
    const std::size_t n = mesh.positions.size();
    if (n == 0 || mesh.indices.empty())
      error(what + " has no triangles");
    if (mesh.normals.size() != n)
      error(what + " has " + std::to_string(mesh.normals.size()) + " normals for " +
            std::to_string(n) + " vertices");
    if (!mesh.uvs.empty() && mesh.uvs.size() != n)
      error(what + " has " + std::to_string(mesh.uvs.size()) + " UVs for " + std::to_string(n) +
            " vertices");
    if (!mesh.tangents.empty() && mesh.tangents.size() != n)
      error(what + " has " + std::to_string(mesh.tangents.size()) + " tangents for " +
            std::to_string(n) + " vertices");
    if (!mesh.colors.empty() && mesh.colors.size() != n)
      error(what + " has " + std::to_string(mesh.colors.size()) + " colors for " +
            std::to_string(n) + " vertices");
    if (mesh.indices.size() % 3 != 0)
      error(what + " has " + std::to_string(mesh.indices.size()) + " indices, not a multiple of 3");
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
      if (mesh.indices[i] >= n) {
        error(what + ": index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
              ", but the mesh has " + std::to_string(n) + " vertices");
        break;
      }
    }
    for (std::size_t v = 0; v < n; ++v) {
      if (!finite(mesh.positions[v])) {
        error(what + ": vertex " + std::to_string(v) + " is not finite");
        break;
      }
    }
  }
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const std::string what = "instance " + std::to_string(i);
    if (instance.mesh >= scene.meshes.size())
      error(what + " uses mesh " + std::to_string(instance.mesh) + ", but there are " +
            std::to_string(scene.meshes.size()));
    if (instance.material >= scene.materials.size())
      error(what + " uses material " + std::to_string(instance.material) + ", but there are " +
            std::to_string(scene.materials.size()));
    if (!finite(instance.objectToWorld))
      error(what + " has a transform that is not finite");
  }
  for (std::size_t m = 0; m < scene.materials.size(); ++m) {
    const MaterialRef& material = scene.materials[m];
    if (material.graphPath.empty() == material.graphText.empty()) {
      error("material " + std::to_string(m) + " ('" + material.name +
            "') needs exactly one of a graph file and graph text");
    }
  }
  if (const std::string problem = cameraProblem(scene.camera); !problem.empty())
    error(problem);
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const Light& light = scene.lights[l];
    const std::string what = "light " + std::to_string(l);
    if (!finite(light.intensity) || light.intensity.x < 0 || light.intensity.y < 0 ||
        light.intensity.z < 0) {
      error(what + " has a negative or non-finite intensity");
    }
    if (light.type == LightType::Directional &&
        !(glm::length(light.direction) > 0.0f && finite(light.direction))) {
      error(what + " is directional but has no direction");
    }
    if (light.type == LightType::Point && !finite(light.position))
      error(what + " has a position that is not finite");
  }
  return diagnostics.errorCount() == errorsBefore;
}

}  // namespace memograph::runtime
