// Links a scene's material graphs into the path tracer: compiles each graph with the
// compiler library (thesis §5.1), and generates "materials.glsl": every compiled include
// followed by evaluateMaterial(), a switch on the scene's material id that calls each
// EvaluateMaterial_<Name> with its first texture slot.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "runtime/scene.h"

namespace memograph::runtime {

struct LinkedMaterial {
  std::string name;     // the EvaluateMaterial_<name> it calls
  int textureBase = 0;  // first slot of its textures in LinkedMaterials::texturePaths
  bool cacheable = false;
};

struct LinkedMaterials {
  std::string source;                     // the generated materials.glsl
  std::vector<LinkedMaterial> materials;  // parallel to Scene::materials
  std::vector<std::string> texturePaths;  // resolved paths, in descriptor-array order
  double compileMilliseconds = 0.0;
};

struct MaterialLinkOptions {
  // A node-library folder that replaces the embedded one (for --nodes DIR); empty: embedded.
  std::filesystem::path nodeLibraryDirectory;
};

// Throws std::runtime_error with the compiler's diagnostics (file:line:col) when a graph is
// missing or does not compile.
LinkedMaterials linkMaterials(const std::vector<MaterialRef>& materials,
                              const MaterialLinkOptions& options = {});

}  // namespace memograph::runtime
