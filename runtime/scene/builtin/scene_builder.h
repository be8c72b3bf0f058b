// Small helper the built-in scene generators use to fill a Scene: keeps mesh and material
// indices, and computes tangents once a mesh is complete.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include <glm/glm.hpp>

#include "runtime/scene/builtin/mesh_builder.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

class SceneBuilder {
 public:
  // `onGeometry`, if set, hears the totals after each mesh (BuiltinSceneOptions::onGeometry).
  explicit SceneBuilder(
      std::function<void(std::uint64_t vertices, std::uint64_t triangles)> onGeometry = {})
      : onGeometry_(std::move(onGeometry)) {}

  // Adds a finished mesh (tangents are computed here) and returns its index.
  std::uint32_t addMesh(Mesh mesh) {
    vertices_ += mesh.positions.size();
    triangles_ += mesh.indices.size() / 3;
    if (onGeometry_)
      onGeometry_(vertices_, triangles_);
    computeTangents(mesh);
    scene_.meshes.push_back(std::move(mesh));
    return static_cast<std::uint32_t>(scene_.meshes.size() - 1);
  }
  // Adds a material once; a second call with the same name returns the first's index.
  std::uint32_t material(const std::string& name, const std::string& graphText) {
    if (auto it = materialIndex_.find(name); it != materialIndex_.end())
      return it->second;
    scene_.materials.push_back(MaterialRef{name, {}, graphText});
    const auto index = static_cast<std::uint32_t>(scene_.materials.size() - 1);
    materialIndex_.emplace(name, index);
    return index;
  }
  void instance(std::uint32_t mesh, std::uint32_t material, const glm::mat4& objectToWorld) {
    scene_.instances.push_back(Instance{mesh, material, objectToWorld});
  }
  Scene& scene() { return scene_; }

 private:
  Scene scene_;
  std::map<std::string, std::uint32_t> materialIndex_;
  std::function<void(std::uint64_t, std::uint64_t)> onGeometry_;
  std::uint64_t vertices_ = 0;
  std::uint64_t triangles_ = 0;
};

// A mesh made of axis-aligned boxes (furniture): {min, max} corner pairs in object space.
struct BoxSpec {
  glm::vec3 min;
  glm::vec3 max;
};
inline Mesh boxesMesh(std::string name, std::initializer_list<BoxSpec> boxes, UvScale uv = {}) {
  Mesh mesh;
  mesh.name = std::move(name);
  for (const BoxSpec& b : boxes)
    appendBox(mesh, b.min, b.max, uv);
  return mesh;
}

}  // namespace memograph::runtime
