// Checks a Scene's invariants before the renderer uploads it, so that a bad scene (from an
// importer, a generator or a hand-built test) is a clear error instead of a GPU fault.
#pragma once

#include <string>

#include "compiler/diagnostics.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

// Adds one error per problem, each naming `sceneName` and the mesh, instance, material or
// light concerned; returns whether the scene is valid. Checks: at least one instance;
// per-vertex arrays as long as `positions` (uvs, tangents and colors may be empty); whole
// triangles with indices in range; finite positions and transforms; instance mesh and
// material indices in range; every material with exactly one of graphPath and graphText;
// a camera that cameraProblem accepts (coordinates in range, a view direction, an up vector
// off it, 0 < fov < 180); lights with finite, non-negative
// intensity and directional lights with a direction.
bool validateScene(const Scene& scene, const std::string& sceneName,
                   compiler::Diagnostics& diagnostics);

}  // namespace memograph::runtime
