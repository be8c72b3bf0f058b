// Writes a Scene as glTF 2.0 (.gltf with its buffer embedded as a data URI), so built-in
// and generated scenes can be inspected in any glTF viewer or Blender, and bundled as
// examples that importScene reads back.
#pragma once

#include <string>

#include "compiler/diagnostics.h"
#include "runtime/scene/scene.h"

namespace memograph::io {

// Meshes become accessors (positions, normals, UVs and tangents when present, uint32
// indices); each instance a node with its matrix and a glTF mesh for its (mesh, material)
// pair; materials are names only (the graphs stay in .mgraph files); the camera a node
// with a perspective camera (aspect 16:9); lights KHR_lights_punctual point and directional
// lights (colour scaled so its largest component is 1, intensity the factor); the constant
// environment goes into the scene's `extras.memographEnvironment`. Written to a temporary
// and renamed: an error leaves no partial file.
bool exportSceneGltf(const runtime::Scene& scene, const std::string& path,
                     compiler::Diagnostics& diagnostics);

}  // namespace memograph::io
