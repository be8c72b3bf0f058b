#include "runtime/materials/material_shaders.h"

#include <chrono>
#include <stdexcept>

#include "runtime/host/parallel_for.h"

namespace memograph::runtime {

std::vector<std::vector<std::uint32_t>> compileMaterialShaders(const ShaderCompiler& base,
                                                               const LinkedMaterials& materials,
                                                               const MaterialShaderRequest& request,
                                                               ShaderCacheStats& stats) {
  const std::size_t count =
      request.units.empty() ? materials.distinct.size() : request.units.size();
  std::vector<std::vector<std::uint32_t>> spirv(count);
  std::vector<ShaderCacheStats> threadStats(workerThreads(request.threads, count));
  const auto start = std::chrono::steady_clock::now();
  parallelFor(count, request.threads, [&](std::size_t index, std::uint32_t thread) {
    // A group's pass is its first member's, but for the constants and texture slots.
    const MaterialInstanceGroup* group =
        request.units.empty() ? nullptr : request.units[index].group;
    const std::size_t distinct = group                   ? group->instances.members.front()
                                 : request.units.empty() ? index
                                                         : request.units[index].distinct;
    const DistinctMaterial& material = materials.distinct[distinct];
    ShaderCompiler compiler =
        base.withFile("material.glsl", group ? group->include : material.include);
    try {
      std::vector<std::string> defines = request.defines;
      if (group) {
        defines.push_back("MG_MATERIAL_INSTANCES=1");
        defines.push_back("MG_MATERIAL_PARAMETER_COUNT=" +
                          std::to_string(group->instances.parameterCount));
      } else {
        defines.push_back("MG_TEXTURE_BASE=" + std::to_string(material.textureBase));
      }
      defines.push_back("MG_EVALUATE_MATERIAL=EvaluateMaterial_" + material.name);
      if (material.cacheable)
        defines.push_back("MG_MATERIAL_CACHEABLE=1");
      if (index < request.materialDefines.size())
        defines.insert(defines.end(), request.materialDefines[index].begin(),
                       request.materialDefines[index].end());
      if (request.cutFunctions && material.cutWidth > 0) {
        defines.push_back("MG_MATERIAL_CUT=MaterialCut_" + material.name);
        defines.push_back("MG_MATERIAL_CUT_WIDTH=" + std::to_string(material.cutWidth));
        defines.push_back("MG_EVALUATE_MATERIAL_CUT=EvaluateMaterialCut_" + material.name);
        defines.push_back("MG_EVALUATE_MATERIAL_REST=EvaluateMaterialRest_" + material.name);
      }
      spirv[index] = compiler.compile({request.source, request.stage, defines});
    } catch (const std::exception& e) {
      throw std::runtime_error(request.what + " of material '" + material.name + "': " + e.what());
    }
    threadStats[thread].hits += compiler.stats().hits;
    threadStats[thread].compiled += compiler.stats().compiled;
  });
  for (const auto& s : threadStats) {
    stats.hits += s.hits;
    stats.compiled += s.compiled;
  }
  // The wall time waited, not the threads' sum: the renderer subtracts it from the set-up's
  // wall time to report pipeline creation (a sum over threads made that negative).
  stats.compileMilliseconds +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return spirv;
}

}  // namespace memograph::runtime
