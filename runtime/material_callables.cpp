#include "runtime/material_callables.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <stdexcept>
#include <thread>

namespace memograph::runtime {

MaterialCallables compileMaterialCallables(const LinkedMaterials& materials,
                                           const MaterialCallableCompileOptions& options,
                                           ShaderCacheStats& stats) {
  MaterialCallables callables;
  const std::size_t count = materials.distinct.size();
  callables.spirv.resize(count);
  for (const LinkedMaterial& material : materials.materials)
    callables.shaderForMaterial.push_back(material.distinctIndex);

  std::uint32_t threadCount = options.threads;
  if (threadCount == 0)
    threadCount = std::max(1u, std::thread::hardware_concurrency());
  threadCount = static_cast<std::uint32_t>(std::min<std::size_t>(threadCount, count));

  // Each material compiles with its own file map holding only its include, so its cache key
  // (a hash of every file the compiler can see) changes only when this material, the
  // embedded shaders or the texture layout change, not when another material does.
  std::atomic<std::size_t> next{0};
  std::vector<ShaderCacheStats> threadStats(threadCount);
  std::vector<std::exception_ptr> errors(threadCount);
  auto work = [&](std::uint32_t thread) {
    try {
      while (true) {
        std::size_t index = next.fetch_add(1);
        if (index >= count)
          return;
        const DistinctMaterial& material = materials.distinct[index];
        std::map<std::string, std::string> files = options.files;
        files["material.glsl"] = material.include;
        ShaderCompiler compiler(std::move(files), options.cacheDirectory);
        try {
          std::vector<std::string> defines = options.defines;
          defines.push_back("MG_TEXTURE_COUNT=" + std::to_string(options.textureCount));
          defines.push_back("MG_TEXTURE_BASE=" + std::to_string(material.textureBase));
          defines.push_back("MG_EVALUATE_MATERIAL=EvaluateMaterial_" + material.name);
          callables.spirv[index] =
              compiler.compile({"material_callable.rcall", ShaderStage::Callable, defines});
        } catch (const std::exception& e) {
          throw std::runtime_error("callable shader of material '" + material.name +
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
  return callables;
}

}  // namespace memograph::runtime
