#include "runtime/materials/material_callables.h"

#include "runtime/materials/material_shaders.h"

namespace memograph::runtime {

MaterialCallables compileMaterialCallables(const LinkedMaterials& materials,
                                           const MaterialCallableCompileOptions& options,
                                           ShaderCacheStats& stats) {
  MaterialCallables callables;
  for (const LinkedMaterial& material : materials.materials)
    callables.shaderForMaterial.push_back(material.distinctIndex);
  MaterialShaderRequest request;
  request.source = "material_callable.rcall";
  request.stage = ShaderStage::Callable;
  request.defines = options.defines;
  request.defines.push_back("MG_TEXTURE_COUNT=" + std::to_string(options.textureCount));
  request.threads = options.threads;
  request.what = "callable shader";
  callables.spirv = compileMaterialShaders(ShaderCompiler(options.files, options.cacheDirectory),
                                           materials, request, stats);
  return callables;
}

}  // namespace memograph::runtime
