// The callable material dispatch (pipeline backend): every distinct material graph compiled
// to its own callable shader (shaders/material_callable.rcall around its include), on
// several threads, each with its own SPIR-V disk-cache entry. The trace pipeline puts them
// in the callable region of its shader-binding table, one record per scene material id.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "runtime/materials/material_linker.h"
#include "runtime/vk/shader_compiler.h"

namespace memograph::runtime {

struct MaterialCallables {
  std::vector<std::vector<std::uint32_t>> spirv;  // one per LinkedMaterials::distinct
  std::vector<std::uint32_t> shaderForMaterial;   // scene material id → index into spirv
};

struct MaterialCallableCompileOptions {
  // The embedded shader sources (material_callable.rcall and what it includes).
  std::map<std::string, std::string> files;
  std::filesystem::path cacheDirectory;  // empty: no disk cache
  std::uint32_t textureCount = 1;
  std::uint32_t threads = 0;  // 0: one per hardware thread
  // Defines every callable shares with the raygen that calls it (those that shape
  // MaterialInputs and MaterialOutputs must match on both sides).
  std::vector<std::string> defines;
};

// Compiles every distinct material; adds the hits, compiles and summed compile time (CPU
// time over all threads) to `stats`. Throws the first compile error (naming the material).
MaterialCallables compileMaterialCallables(const LinkedMaterials& materials,
                                           const MaterialCallableCompileOptions& options,
                                           ShaderCacheStats& stats);

}  // namespace memograph::runtime
