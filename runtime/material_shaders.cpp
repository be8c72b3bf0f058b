#include "runtime/material_shaders.h"

#include <stdexcept>

#include "runtime/parallel_for.h"

namespace memograph::runtime {

std::vector<std::vector<std::uint32_t>> compileMaterialShaders(const ShaderCompiler& base,
                                                               const LinkedMaterials& materials,
                                                               const MaterialShaderRequest& request,
                                                               ShaderCacheStats& stats) {
  const std::size_t count = materials.distinct.size();
  std::vector<std::vector<std::uint32_t>> spirv(count);
  std::vector<ShaderCacheStats> threadStats(workerThreads(request.threads, count));
  parallelFor(count, request.threads, [&](std::size_t index, std::uint32_t thread) {
    const DistinctMaterial& material = materials.distinct[index];
    ShaderCompiler compiler = base.withFile("material.glsl", material.include);
    try {
      std::vector<std::string> defines = request.defines;
      defines.push_back("MG_TEXTURE_BASE=" + std::to_string(material.textureBase));
      defines.push_back("MG_EVALUATE_MATERIAL=EvaluateMaterial_" + material.name);
      spirv[index] = compiler.compile({request.source, request.stage, defines});
    } catch (const std::exception& e) {
      throw std::runtime_error(request.what + " of material '" + material.name + "': " + e.what());
    }
    threadStats[thread].hits += compiler.stats().hits;
    threadStats[thread].compiled += compiler.stats().compiled;
    threadStats[thread].compileMilliseconds += compiler.stats().compileMilliseconds;
  });
  for (const auto& s : threadStats) {
    stats.hits += s.hits;
    stats.compiled += s.compiled;
    stats.compileMilliseconds += s.compileMilliseconds;
  }
  return spirv;
}

}  // namespace memograph::runtime
