#include "runtime/trace/wavefront/wavefront_passes.h"

#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

std::vector<std::uint32_t> wavefrontComputePasses(const WavefrontPipelineChoice& choice) {
  const bool materials = choice.materialPasses > 0;
  std::vector<std::uint32_t> passes;
  for (std::uint32_t pass = 0; pass < gpu::kWavefrontPassCount; ++pass) {
    const bool traces = pass == gpu::kWavefrontTrace || pass == gpu::kWavefrontShadow ||
                        pass == gpu::kWavefrontTracedInputs;
    const bool binning = pass == gpu::kWavefrontBinCount || pass == gpu::kWavefrontBinOffsets ||
                         pass == gpu::kWavefrontBinScatter;
    if (choice.ambientOcclusionIntegrator) {
      const bool used = pass == gpu::kWavefrontGenerate || pass == gpu::kWavefrontFinish ||
                        ((pass == gpu::kWavefrontTrace || pass == gpu::kWavefrontTracedInputs) &&
                         choice.rayQuery);
      if (used)
        passes.push_back(pass);
      continue;
    }
    if ((traces && !choice.rayQuery) || (binning && !materials) ||
        pass == gpu::kWavefrontMaterial ||
        (pass == gpu::kWavefrontLookup && !choice.cacheLookups) ||
        (pass == gpu::kWavefrontTracedInputs && !(materials && choice.tracedInputs)))
      continue;
    passes.push_back(pass);
  }
  return passes;
}

std::uint32_t wavefrontPipelineCount(const WavefrontPipelineChoice& choice) {
  return static_cast<std::uint32_t>(wavefrontComputePasses(choice).size()) + choice.materialPasses +
         (choice.rayQuery ? 0u : 1u);
}

}  // namespace memograph::runtime
