// Checks a glTF/glb file before it reaches assimp (docs/guide/limits.md). assimp
// allocates what a .glb header declares, recurses once per level of the node hierarchy
// (a deep one overflows the stack) and follows indices without checking all of them, so
// what it would trust is checked here first, cheaply and without recursion:
//  - .glb: the header's length and each chunk's length within the file, the first chunk
//    JSON (a 4 GiB chunk declared in 28 bytes is refused before anything is allocated);
//  - the JSON valid (tools/io/json_reader.h: strict, nested at most kMaxJsonDepth deep);
//  - the node hierarchy: children in range, no node with two parents, no cycle, at most
//    kMaxNodeDepth levels;
//  - every index into nodes, meshes, cameras, materials, accessors, bufferViews and
//    buffers in range, accessors within their buffer views, views within their buffers;
//  - buffers in external files (a non-data: uri, resolved against the glTF's folder as
//    assimp does): regular files within the scene limit, as long as byteLength, the URI not
//    an absolute path;
//  - each primitive's vertex indices below its vertex count, read from data: URIs, the
//    .glb BIN chunk and external files.
#pragma once

#include <string>

#include "compiler/diagnostics.h"

namespace memograph::io {

inline constexpr int kMaxNodeDepth = 1000;

// True for files to check (extension .gltf or .glb); false with an error added otherwise.
bool precheckGltf(const std::string& path, compiler::Diagnostics& diagnostics);

// The same checks on bytes in memory (the fuzz target and tests); `path` names them, and
// external buffers are looked up in its folder.
bool precheckGltfBytes(const std::string& path, const std::string& bytes, bool glb,
                       compiler::Diagnostics& diagnostics);

}  // namespace memograph::io
