// One shader per distinct material graph, compiled on several threads: the entry source (a
// material callable, or a wavefront material pass) around that graph's include
// ("material.glsl"), each with its own SPIR-V disk-cache entry. Every distinct graph of a
// scene becomes a small shader of its own, so no compile ever sees all of a scene's graphs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/materials/material_linker.h"
#include "runtime/vk/shader_compiler.h"

namespace memograph::runtime {

// One shader to compile: an instance group's shared pass, or (group null) distinct graph
// `distinct`'s own.
struct MaterialShaderUnit {
  const MaterialInstanceGroup* group = nullptr;
  std::uint32_t distinct = 0;
};

struct MaterialShaderRequest {
  std::string source;  // the entry file among `base`'s files
  ShaderStage stage = ShaderStage::Compute;
  // Defines every material's shader shares; each also gets MG_TEXTURE_BASE (its first
  // texture slot) and MG_EVALUATE_MATERIAL (its EvaluateMaterial_<Name>), and with
  // cutFunctions its cut's.
  std::vector<std::string> defines;
  // The texel cache keys cuts (MG_CACHE_CUTS; the wavefront's material passes): a material
  // with a cut also gets MG_MATERIAL_CUT (its MaterialCut_<Name>), MG_MATERIAL_CUT_WIDTH,
  // MG_EVALUATE_MATERIAL_CUT and MG_EVALUATE_MATERIAL_REST.
  bool cutFunctions = false;
  // The shaders to compile (empty: one per distinct graph). The wavefront's material passes
  // bin by distinct graph and dispatch each bin with its index (push.step.w); a group's
  // shared pass gets MG_MATERIAL_INSTANCES and its parameter count
  // (MG_MATERIAL_PARAMETER_COUNT) instead of MG_TEXTURE_BASE, and takes each bin's texture
  // slot and constants in push constants (shared_types.h, kMaterialParameterPushOffset).
  std::vector<MaterialShaderUnit> units;
  // Per shader (distinct material, or instance group; empty: none), defines of that shader
  // alone.
  std::vector<std::vector<std::string>> materialDefines;
  std::uint32_t threads = 0;    // 0: one per hardware thread
  std::string what = "shader";  // names the shader in a compile error: "<what> of material 'X'"
};

// Compiles `request.source` once per LinkedMaterials::distinct (in that order), or per
// request.units entry, with a compiler
// that sees `base`'s files plus the material's include as "material.glsl", so its cache key
// changes only when this material, the shared sources or the defines change. Adds the hits,
// compiles and summed compile time (CPU time over all threads) to `stats`. Throws the first
// compile error, naming the material.
std::vector<std::vector<std::uint32_t>> compileMaterialShaders(const ShaderCompiler& base,
                                                               const LinkedMaterials& materials,
                                                               const MaterialShaderRequest& request,
                                                               ShaderCacheStats& stats);

}  // namespace memograph::runtime
