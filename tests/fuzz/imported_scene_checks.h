// What the scene-import fuzz targets require of io::importScene's result.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "tools/io/scene_import.h"

namespace memograph::fuzz {

// A failed import carries an error; an accepted scene holds only what the renderer relies
// on without checking again: every vertex index below its mesh's vertex count, every
// instance's mesh and material in range. Aborts, saying which rule broke.
inline void checkImportedScene(const std::optional<runtime::Scene>& scene,
                               const compiler::Diagnostics& diagnostics) {
  if (!scene) {
    if (!diagnostics.hasErrors()) {
      std::fprintf(stderr, "import failed without an error\n");
      std::abort();
    }
    return;
  }
  for (const auto& mesh : scene->meshes) {
    for (std::uint32_t index : mesh.indices) {
      if (index >= mesh.positions.size()) {
        std::fprintf(stderr, "accepted a vertex index %u of %zu vertices\n", index,
                     mesh.positions.size());
        std::abort();
      }
    }
  }
  for (const auto& instance : scene->instances) {
    if (instance.mesh >= scene->meshes.size() || instance.material >= scene->materials.size()) {
      std::fprintf(stderr, "accepted an instance out of range\n");
      std::abort();
    }
  }
}

}  // namespace memograph::fuzz
