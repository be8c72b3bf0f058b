// Which of wavefront.glsl's passes a wavefront tracer builds a pipeline for, and how many
// pipelines it creates in all: the passes a frame of its configuration records, no others
// (no binning without material graphs, no lookup without a cache, no traced-inputs pass
// without a material that reads a traced input, no trace, shadow or traced-inputs compute
// pass where the ray-tracing pipeline's raygens trace). The first frame's cold start is
// mostly these pipelines' creation (docs/design/path-tracer.md, "Pipeline cache").
#pragma once

#include <cstdint>
#include <vector>

namespace memograph::runtime {

// What decides the wavefront's pipelines.
struct WavefrontPipelineChoice {
  bool rayQuery = true;  // the query backend: trace and shadow are compute passes
  // Material passes: one per instance group of distinct graphs (graphs of one shape share
  // one, LinkedMaterials::instanceGroups); 0: the floor.
  std::uint32_t materialPasses = 0;
  bool cacheLookups = false;  // a cache's lookup pass (WavefrontSetup::cacheLookups)
  // With material graphs, some reads a traced input (LinkedMaterials::tracedInputs): the
  // traced-inputs pass, a compute pass on the query backend, a third raygen of the
  // ray-tracing pipeline on the pipeline backend (no pipeline of its own there).
  bool tracedInputs = false;
  // The AO integrator (--integrator ao; no material graphs): a round is generate, trace, the
  // traced-inputs pass (there the integrator's AO rays) and finish, no shading passes.
  bool ambientOcclusionIntegrator = false;
};

// The compute passes (gpu::kWavefront* indices, ascending) that get a pipeline of their own;
// kWavefrontMaterial never does: each instance group has its material pipeline.
std::vector<std::uint32_t> wavefrontComputePasses(const WavefrontPipelineChoice& choice);

// Every pipeline the tracer creates: the compute passes, the material passes, and on
// the pipeline backend the one ray-tracing pipeline of the trace and shadow raygens.
std::uint32_t wavefrontPipelineCount(const WavefrontPipelineChoice& choice);

}  // namespace memograph::runtime
