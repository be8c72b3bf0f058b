#include "runtime/material_shaders.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <stdexcept>
#include <thread>

namespace memograph::runtime {

std::vector<std::vector<std::uint32_t>> compileMaterialShaders(const ShaderCompiler& base,
                                                               const LinkedMaterials& materials,
                                                               const MaterialShaderRequest& request,
                                                               ShaderCacheStats& stats) {
  const std::size_t count = materials.distinct.size();
  std::vector<std::vector<std::uint32_t>> spirv(count);
  std::uint32_t threadCount = request.threads;
  if (threadCount == 0)
    threadCount = std::max(1u, std::thread::hardware_concurrency());
  threadCount = static_cast<std::uint32_t>(std::min<std::size_t>(threadCount, count));

  std::atomic<std::size_t> next{0};
  std::vector<ShaderCacheStats> threadStats(std::max(threadCount, 1u));
  std::vector<std::exception_ptr> errors(std::max(threadCount, 1u));
  auto work = [&](std::uint32_t thread) {
    try {
      while (true) {
        const std::size_t index = next.fetch_add(1);
        if (index >= count)
          return;
        const DistinctMaterial& material = materials.distinct[index];
        ShaderCompiler compiler = base.withFile("material.glsl", material.include);
        try {
          std::vector<std::string> defines = request.defines;
          defines.push_back("MG_TEXTURE_BASE=" + std::to_string(material.textureBase));
          defines.push_back("MG_EVALUATE_MATERIAL=EvaluateMaterial_" + material.name);
          spirv[index] = compiler.compile({request.source, request.stage, defines});
        } catch (const std::exception& e) {
          throw std::runtime_error(request.what + " of material '" + material.name +
                                   "': " + e.what());
        }
        threadStats[thread].hits += compiler.stats().hits;
        threadStats[thread].compiled += compiler.stats().compiled;
        threadStats[thread].compileMilliseconds += compiler.stats().compileMilliseconds;
      }
    } catch (...) {
      errors[thread] = std::current_exception();
      next = count;  // the others stop after their current material
    }
  };
  if (threadCount <= 1) {
    if (count > 0)
      work(0);
  } else {
    std::vector<std::thread> threads;
    for (std::uint32_t t = 0; t < threadCount; ++t)
      threads.emplace_back(work, t);
    for (auto& thread : threads)
      thread.join();
  }
  for (const auto& error : errors) {
    if (error)
      std::rethrow_exception(error);
  }
  for (const auto& s : threadStats) {
    stats.hits += s.hits;
    stats.compiled += s.compiled;
    stats.compileMilliseconds += s.compileMilliseconds;
  }
  return spirv;
}

}  // namespace memograph::runtime
