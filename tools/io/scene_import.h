// Scene import through assimp (glTF 2.0 .gltf/.glb, Wavefront .obj, and whatever else
// assimp reads): meshes, the node hierarchy as instances with world transforms, normals,
// UVs, tangents, vertex colours, cameras, point and directional lights, and material names
// mapped to material graphs in a materials folder.
#pragma once

#include <optional>
#include <string>

#include "compiler/diagnostics.h"
#include "runtime/scene/scene.h"

namespace memograph::io {

// The material that stands in for every material whose graph is missing.
inline constexpr const char* kMissingMaterialName = "MissingMaterial";

// Imports `path`. Each scene material named N maps to `<materialsDir>/N.mgraph` (N with
// path separators replaced by '_'); when that file does not exist the instances using it
// get the shared magenta-checker material kMissingMaterialName and a warning names N and
// the file looked for. Meshes without normals get smooth ones; meshes with UVs but without
// tangents get them generated. Lights and cameras follow their nodes' transforms; the first
// camera becomes Scene::camera (a warning names the others), and without one the camera
// frames the scene's bounds. Returns nothing after adding an error: a missing file, a file
// assimp cannot read, or one without triangles.
std::optional<runtime::Scene> importScene(const std::string& path, const std::string& materialsDir,
                                          compiler::Diagnostics& diagnostics);

}  // namespace memograph::io
