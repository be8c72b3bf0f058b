// Checks a Wavefront OBJ file and its material libraries before assimp reads them
// (docs/guide/limits.md), as gltf_precheck does for glTF. assimp opens what an OBJ names
// without asking what it is: a `mtllib` naming a FIFO blocks the import forever, and
// /dev/zero never ends. So, without recursion and reading each file once:
//  - every `mtllib` file, and every texture an MTL names (`map_*`, `bump`, `disp`, `decal`,
//    `refl`): a relative name (an absolute one is refused, as for glTF buffers), resolved
//    against the referring file's folder as assimp does; where it exists, a regular file
//    (no FIFO, device or folder) within the scene limit. A missing material library or
//    texture is a warning: assimp goes on without it, and memograph takes materials from
//    graphs, not from MTL textures;
//  - the meshes the OBJ will become (one per material switch within an object or group,
//    as assimp's OBJ reader splits them) at most kMaxSceneMeshes, refused at the line of
//    the first one past it, before assimp allocates them.
// Errors name file:line:col.
#pragma once

#include <string>

#include "compiler/diagnostics.h"

namespace memograph::io {

// True for files that pass or are not OBJ (extension other than .obj); false with errors
// added otherwise.
bool precheckObj(const std::string& path, compiler::Diagnostics& diagnostics);

// The same checks on bytes in memory (the fuzz target and tests); `path` names them, and
// material libraries are looked up in its folder.
bool precheckObjBytes(const std::string& path, const std::string& bytes,
                      compiler::Diagnostics& diagnostics);

}  // namespace memograph::io
