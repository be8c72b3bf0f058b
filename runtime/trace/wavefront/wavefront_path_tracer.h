// The wavefront path tracer on the host (--shading wavefront): the passes of
// shaders/wavefront.glsl, their buffers (path state, queues, indirect arguments) and the
// command sequence of a frame, with a timestamp after every pass. Memory-resident path state
// against the megakernel (Laine, Karras and Aila, "Megakernels Considered Harmful", HPG
// 2013): with the free-material floor's constants, or with the scene's material graphs,
// each evaluated by a small compute pipeline of its own over the hits sorted by material.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/materials/material_linker.h"
#include "runtime/materials/material_shaders.h"
#include "runtime/trace/frame_tracer.h"
#include "runtime/trace/render_stats.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/spirv_size.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// What the wavefront renders beyond the megakernel's defines.
struct WavefrontSetup {
  // Null: the floor (MG_MATERIAL_FLOOR in the defines); otherwise the scene's linked graphs,
  // one material pipeline per instance group (graphs of one shape).
  const LinkedMaterials* materials = nullptr;
  // Graphs of one shape share a material pipeline (LinkedMaterials::instanceGroups); false:
  // each distinct graph has its own, as a check of the sharing compares.
  bool materialInstances = true;
  // With materialInstances: the first frame binds the shared passes, and before the second
  // each graph of a shared pass gets its own (createDeferredPipelines). A shared pass starts
  // sooner, a graph's own pass runs faster (docs/design/wavefront.md, "Material instances").
  bool ownPassesFromSecondFrame = false;
  // A cache's defines (MG_CACHE_TEXEL, or MG_CACHE_TILE with MG_TILE_FILL_DEFERRED), with
  // materials: a lookup pass before the binning; the material passes insert the texel
  // cache's misses, or compute the tiles the lookups queued (tileQueueCapacity of them at
  // most a bounce: the sorted tile list's length).
  bool cacheLookups = false;
  std::uint32_t tileQueueCapacity = 0;
  bool tileImage = false;  // the tile cache stores its texels in an image (a binding more)
  // With materials: some emitter's emission NEE must take from its graph
  // (MG_NEE_EVALUATES_EMISSION in the defines): after each bounce's shadow pass its unblocked
  // samples' points are binned and their emitters' graphs evaluated by the material passes.
  bool emitterGraphs = false;
  // With emitterGraphs, per distinct graph whether some emitter's light samples evaluate it
  // (SceneMaterials::neeEvaluatedGraphs; empty: every graph): only those graphs' material
  // passes compile the evaluation of light points (MG_MATERIAL_LIGHT_POINTS).
  std::vector<bool> lightPointGraphs;
  // --shared-primary (RenderSettings::sharedPrimaryRay): round 0 traces each pixel's camera ray
  // and keeps its hit in two more fields, which the later rounds take instead of tracing it.
  bool sharedPrimaryHits = false;
  // Filter Glossy (MG_FILTER_GLOSSY_INVERSE in the defines): one more field after the others
  // keeps each path's smallest bounce pdf (PathState::minRayPdf) from one bounce to the next.
  bool minRayPdf = false;
  // The texel cache keys materials by their cut (MG_CACHE_CUTS in the defines): the lookup
  // pass reads a cut material's values, and its material pass evaluates the cut on a miss
  // and the rest always, through the cut functions of its graph's include.
  bool cutKeys = false;
  // With cutKeys and unfiltered reads: the lookup pass stores a found cut entry's values, and
  // a material pass the values it reads or evaluates, in ceil(cutValueCount / 4) fields of
  // their own (MG_WAVEFRONT_CUT_FIELD), and the shade pass runs the rest of each graph whose
  // rest it holds (LinkedMaterial::restInShade, material_rests.glsl) from them: a hit moves
  // its cut's few floats instead of all of MaterialOutputs.
  bool cutValuesToShade = false;
  // The path state's capacity, paths in flight (0: every pixel, or as many as the device's
  // storage-buffer range and work-group count allow); a round over more pixels runs in
  // chunks of at most that many, one after another.
  std::uint32_t pathSlots = 0;
  // The AO integrator (--integrator ao, MG_INTEGRATOR_AO in the defines; no materials): a
  // round is generate, trace, the traced-inputs pass computing each hit's AO, and finish.
  bool ambientOcclusionIntegrator = false;
  // Threads compiling the GLSL and creating the pipelines; 0: one per core.
  std::uint32_t compileThreads = 0;
};

class WavefrontPathTracer final : public FrameTracer {
 public:
  // Compiles the passes for the context's backend: every pass a compute pipeline on the query
  // backend; on the pipeline backend trace and shadow are the raygens of one ray-tracing
  // pipeline, launched with vkCmdTraceRaysIndirectKHR (refused, std::runtime_error, where the
  // device lacks it). `extraDefines` as the megakernel's (floor, cache, NEE, object inputs).
  // The material shaders compile from `compiler`'s files plus each graph's include; the
  // GLSL compiles, then the pipelines (all of them at once, with the context's pipeline
  // cache), run on `setup.compileThreads` threads. Throws std::invalid_argument when a given
  // capacity does not fit the device, or for a texel cache without materials.
  WavefrontPathTracer(const VulkanContext& context, ShaderCompiler& compiler,
                      std::uint32_t textureCount, const std::vector<std::string>& extraDefines,
                      std::uint32_t width, std::uint32_t height, const WavefrontSetup& setup);

  VkDescriptorSetLayout descriptorSetLayout() const override { return setLayout_.get(); }
  // Paths in flight (the path state's slots) and the chunks a round of the image takes.
  std::uint32_t pathSlots() const { return slots_; }
  std::uint32_t chunks() const { return chunks_; }
  const GpuBuffer& pathState() const { return pathState_; }
  const GpuBuffer& pathQueues() const { return pathQueues_; }
  const GpuBuffer& control() const { return control_; }

  // Timestamps record() writes into its pool from `firstQuery` on: one before the first pass,
  // one after each pass.
  std::uint32_t timestampCount(std::uint32_t paths, std::uint32_t bounces) const override;

  // Material bins (distinct graphs); 0 with the floor.
  std::uint32_t materialBinCount() const { return materialBins_; }
  // Material pipelines: one per instance group (graphs of one shape share one).
  std::uint32_t materialPassCount() const {
    return static_cast<std::uint32_t>(materialPasses_.size());
  }
  // Hits each bin's material pass evaluated in the last frame record() recorded (read after
  // it completed); empty with the floor.
  std::vector<std::uint32_t> binHits() const;
  // The material pipelines' GLSL compiles (they have compilers of their own).
  const ShaderCacheStats& materialShaderStats() const { return materialShaderStats_; }
  // Per material pass (instance group), its SPIR-V as a driver that inlines every call compiles it
  // (spirv_size.h): the pass, and its graph (EvaluateMaterial_<name>) within it.
  struct MaterialPassSize {
    SpirvSize pass;
    SpirvFunctionCopies graph;
  };
  const std::vector<MaterialPassSize>& materialPassSizes() const { return materialPassSizes_; }

  // Records one frame: per chunk of pixels, P rounds of one path a pixel, each generate, L x
  // (trace, [[lookup,] bin count, bin offsets, bin scatter, [traced inputs,] material passes,]
  // shade, queue,
  // shadow[, the light points' bin count, offsets, scatter and material passes]), finish, with
  // a barrier between passes. `countsHits`: the trace passes count LiPaC's hit feedback (a
  // tracer built with MG_HIT_FEEDBACK; the frame counts). `timestamps` VK_NULL_HANDLE: none.
  // `pixels`: the image's (0: the frame's; a sparse look's are fewer, FrameTrace::width).
  void record(VkCommandBuffer commands, VkDescriptorSet set, std::uint32_t paths,
              std::uint32_t bounces, bool countsHits, VkQueryPool timestamps,
              std::uint32_t firstQuery, std::uint32_t pixels = 0) const;

  // Adds the passes' GPU times to `frame` (its wavefront*Milliseconds) from the timestamps
  // record() wrote, read back as `ticks` (timestampCount of them).
  void addPassTimes(const std::vector<std::uint64_t>& ticks, std::uint32_t paths,
                    std::uint32_t bounces, double millisecondsPerTick, FrameStats& frame) const;

  // FrameTracer: the path state, queues and control in the set; no megakernel dispatches;
  // record() for the frame's P and L (a look: one round, its rays counted, no light
  // samples; frame.culling says so); the bins' hits and the passes' times.
  void addResources(TraceResources& resources) const override;
  std::uint32_t dispatchCount(const FrameTrace&) const override { return 0; }
  void recordTrace(VkCommandBuffer commands, VkDescriptorSet set, const FrameTrace& trace,
                   VkQueryPool timestamps, std::uint32_t firstTimestamp) const override {
    record(commands, set, trace.paths, trace.rays, trace.counts, timestamps, firstTimestamp,
           trace.width * trace.height);
  }
  void addFrameStats(const FrameTrace& trace, const std::vector<std::uint64_t>* passTicks,
                     double millisecondsPerTick, FrameStats& stats) const override;
  // With WavefrontSetup::ownPassesFromSecondFrame: each graph of a shared material pass gets
  // a pass of its own, compiled and created now, and the shared passes go. Returns the
  // pipelines created (0 where no pass was shared, or on a second call).
  std::uint32_t createDeferredPipelines() override;

 private:
  const VulkanContext& context_;
  bool query_ = true;
  bool lookup_ = false;       // the texel cache's lookup pass
  bool lightPoints_ = false;  // WavefrontSetup::emitterGraphs
  // Some material reads a traced input: the traced-inputs pass after the hits' scatter.
  bool tracedInputs_ = false;
  // The AO integrator: rounds of generate, trace, the traced-inputs pass (its AO rays over
  // the live queue) and finish.
  bool ambientOcclusionIntegrator_ = false;
  std::uint32_t pixels_ = 0;
  std::uint32_t slots_ = 0;   // paths in flight: a pixel's each, up to the capacity
  std::uint32_t chunks_ = 1;  // chunks of at most slots_ pixels a round takes
  VulkanHandle<VkDescriptorSetLayout> setLayout_;
  VulkanHandle<VkPipelineLayout> layout_;
  // Indexed by gpu::kWavefront*; trace and shadow empty on the pipeline backend.
  std::vector<VulkanHandle<VkPipeline>> computePasses_;
  // One per instance group of distinct graphs (LinkedMaterials::instanceGroups); empty with
  // the floor. Each runs over the bins (distinct graphs) of its group, binsOfPass_.
  std::vector<VulkanHandle<VkPipeline>> materialPasses_;
  std::vector<std::vector<std::uint32_t>> binsOfPass_;
  std::vector<std::string> materialPassNames_;  // each pass's EvaluateMaterial_<name>
  std::uint32_t materialBins_ = 0;
  // Per bin, what its dispatch pushes after the WavefrontPush where its pass is an instance
  // group's (shared_types.h, kMaterialParameterPushOffset); empty for a pass of its own.
  std::vector<std::vector<std::uint32_t>> binInstances_;
  std::uint32_t pushBytes_ = sizeof(gpu::WavefrontPush);  // the pipeline layout's push range
  ShaderCacheStats materialShaderStats_;
  std::vector<MaterialPassSize> materialPassSizes_;
  // What createDeferredPipelines compiles the graphs' own passes with (the material passes'
  // defines, and the set-up with its linked graphs); empty once they exist, or where none is
  // due.
  struct DeferredOwnPasses {
    ShaderCompiler compiler;
    std::vector<std::string> defines;
    WavefrontSetup setup;
  };
  std::optional<DeferredOwnPasses> deferredOwnPasses_;
  VulkanHandle<VkPipeline> rayTracing_;  // pipeline backend: the trace and shadow raygens
  GpuBuffer shaderBindingTable_;
  VkStridedDeviceAddressRegionKHR traceRaygenRegion_{};
  VkStridedDeviceAddressRegionKHR shadowRaygenRegion_{};
  VkStridedDeviceAddressRegionKHR tracedInputsRaygenRegion_{};
  VkStridedDeviceAddressRegionKHR missRegion_{};
  VkStridedDeviceAddressRegionKHR hitRegion_{};
  GpuBuffer pathState_;
  GpuBuffer pathQueues_;
  GpuBuffer control_;
  GpuBuffer binReadback_;  // host-visible copy of the bins' records after a frame

  // The shaders of every pipeline, compiled before any pipeline is created.
  struct PipelineShaders {
    std::vector<std::uint32_t> passes;                      // the compute passes (gpu::kWavefront*)
    std::vector<std::vector<std::uint32_t>> passSpirv;      // one a compute pass
    std::vector<std::vector<std::uint32_t>> materialSpirv;  // one a material pass
    // Pipeline backend: the trace and shadow raygens, the misses and the hit.
    std::vector<VulkanHandle<VkShaderModule>> rayTracingModules;
    std::vector<VkShaderStageFlagBits> rayTracingStages;
  };
  // Which material passes there are (binsOfPass_, binInstances_, pushBytes_) and what each
  // compiles: an instance group's shared pass where its parameters fit the push constants,
  // else a pass per distinct graph.
  std::vector<MaterialShaderUnit> planMaterialPasses(const LinkedMaterials& materials,
                                                     bool instances);
  // One shader per unit (a material pass), from its include alone; `binsOfUnit` the bins each
  // unit's pass runs over.
  std::vector<std::vector<std::uint32_t>> compileMaterialPasses(
      ShaderCompiler& compiler, const LinkedMaterials& materials,
      const std::vector<MaterialShaderUnit>& units,
      const std::vector<std::vector<std::uint32_t>>& binsOfUnit,
      const std::vector<std::string>& defines, const WavefrontSetup& setup);
  // The pipeline backend's trace and shadow raygens (with `tracesFromHits` the traced-inputs
  // raygen) and the report-only shaders, as compile requests appended to `requests`, with
  // their stages.
  static void appendRayTracingRequests(const std::vector<std::string>& defines, bool tracesFromHits,
                                       std::vector<ShaderCompileRequest>& requests,
                                       std::vector<VkShaderStageFlagBits>& stages);
  // Every pipeline (compute passes, material passes, the ray-tracing pipeline and its
  // table) at once, on up to `threads` threads.
  void createPipelines(const PipelineShaders& shaders, std::uint32_t threads);
  // One pass of a frame; `lightPoints`: a binning or material pass over the light samples'
  // points (WavefrontSetup::emitterGraphs).
  struct FramePass {
    std::uint32_t pass = 0;  // gpu::kWavefront*
    bool lightPoints = false;
  };
  // The passes of an image of `pixels`, in chunks of at most slots_.
  std::vector<FramePass> framePasses(std::uint32_t paths, std::uint32_t bounces,
                                     std::uint32_t pixels) const;
  void recordPass(VkCommandBuffer commands, std::uint32_t pass, std::uint32_t pixels,
                  std::uint32_t chunk, std::uint32_t round, std::uint32_t bounce, bool countsHits,
                  bool lightPoints) const;
};

}  // namespace memograph::runtime
