#include "runtime/trace/wavefront/wavefront_path_tracer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <stdexcept>

#include "runtime/host/parallel_for.h"
#include "runtime/materials/material_shaders.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/megakernel/trace_pipelines.h"
#include "runtime/trace/wavefront/wavefront_passes.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/thread_pipeline_caches.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

// The define that selects each pass of wavefront.glsl, indexed by gpu::kWavefront*.
constexpr std::array<const char*, gpu::kWavefrontPassCount> kPassDefines = {
    "MG_WAVEFRONT_GENERATE=1",  "MG_WAVEFRONT_TRACE=1",       "MG_WAVEFRONT_SHADE=1",
    "MG_WAVEFRONT_QUEUE=1",     "MG_WAVEFRONT_SHADOW=1",      "MG_WAVEFRONT_FINISH=1",
    "MG_WAVEFRONT_BIN_COUNT=1", "MG_WAVEFRONT_BIN_OFFSETS=1", "MG_WAVEFRONT_BIN_SCATTER=1",
    "MG_WAVEFRONT_MATERIAL=1",  "MG_WAVEFRONT_LOOKUP=1",      "MG_WAVEFRONT_TRACED_INPUTS=1"};
constexpr std::array<const char*, gpu::kWavefrontPassCount> kPassNames = {
    "wavefront generate",  "wavefront trace",       "wavefront shade",
    "wavefront queue",     "wavefront shadow",      "wavefront finish",
    "wavefront bin count", "wavefront bin offsets", "wavefront bin scatter",
    "wavefront material",  "wavefront lookup",      "wavefront traced inputs"};

// Where each pass's GPU time goes in FrameStats, indexed by gpu::kWavefront*: the three
// binning passes together, the material passes of a bounce together.
constexpr std::array<double FrameStats::*, gpu::kWavefrontPassCount> kPassTimes = {
    &FrameStats::wavefrontGenerateMilliseconds, &FrameStats::wavefrontTraceMilliseconds,
    &FrameStats::wavefrontShadeMilliseconds,    &FrameStats::wavefrontQueueMilliseconds,
    &FrameStats::wavefrontShadowMilliseconds,   &FrameStats::wavefrontFinishMilliseconds,
    &FrameStats::wavefrontBinMilliseconds,      &FrameStats::wavefrontBinMilliseconds,
    &FrameStats::wavefrontBinMilliseconds,      &FrameStats::wavefrontMaterialMilliseconds,
    &FrameStats::wavefrontLookupMilliseconds,   &FrameStats::wavefrontTracedInputsMilliseconds};

// The bytes of a bin's record after gpu::WavefrontControl: its material pass's dispatch
// arguments, its hits' counts and its queued tiles' counts (shared_types.h).
constexpr std::uint64_t kBinRecordBytes = 3 * 16;

std::uint32_t workgroupsFor(std::uint64_t invocations) {
  return static_cast<std::uint32_t>((invocations + gpu::kWavefrontWorkgroupSize - 1) /
                                    gpu::kWavefrontWorkgroupSize);
}

}  // namespace

// The passes of a frame in recording order (the timestamp after each says when it ended);
// kWavefrontMaterial stands for every bin's material pass of the bounce; `lookup`: the texel
// cache's lookup before the binning; with traced inputs their pass between the hits' scatter
// and the material passes; `lightPoints`: after the shadow pass the light samples'
// points are binned and their emitters' graphs evaluated. Every chunk of pixels runs all P
// rounds before the next.
std::vector<WavefrontPathTracer::FramePass> WavefrontPathTracer::framePasses(
    std::uint32_t paths, std::uint32_t bounces, std::uint32_t pixels) const {
  const bool materials = !materialPasses_.empty();
  const std::uint32_t chunks = (pixels + slots_ - 1) / slots_;
  std::vector<FramePass> passes;
  auto binning = [&](bool lightPoints) {
    for (std::uint32_t pass :
         {gpu::kWavefrontBinCount, gpu::kWavefrontBinOffsets, gpu::kWavefrontBinScatter})
      passes.push_back({pass, lightPoints});
    // A light point's emitter graph reads no traced input (the megakernel traces none for it).
    if (tracedInputs_ && !lightPoints)
      passes.push_back({gpu::kWavefrontTracedInputs});
    passes.push_back({gpu::kWavefrontMaterial, lightPoints});
  };
  for (std::uint32_t round = 0; round < chunks * paths; ++round) {
    passes.push_back({gpu::kWavefrontGenerate});
    if (ambientOcclusionIntegrator_) {
      // The AO integrator: the camera rays' hits and their AO rays, nothing shaded.
      for (std::uint32_t pass :
           {gpu::kWavefrontTrace, gpu::kWavefrontTracedInputs, gpu::kWavefrontFinish})
        passes.push_back({pass});
      continue;
    }
    for (std::uint32_t bounce = 0; bounce < bounces; ++bounce) {
      passes.push_back({gpu::kWavefrontTrace});
      if (materials) {
        if (lookup_)
          passes.push_back({gpu::kWavefrontLookup});
        binning(false);
      }
      passes.push_back({gpu::kWavefrontShade});
      passes.push_back({gpu::kWavefrontQueue});
      passes.push_back({gpu::kWavefrontShadow});
      if (lightPoints_)
        binning(true);
    }
    passes.push_back({gpu::kWavefrontFinish});
  }
  return passes;
}

WavefrontPathTracer::WavefrontPathTracer(const VulkanContext& context, ShaderCompiler& compiler,
                                         std::uint32_t textureCount,
                                         const std::vector<std::string>& extraDefines,
                                         std::uint32_t width, std::uint32_t height,
                                         const WavefrontSetup& setup)
    : context_(context),
      query_(context.backend() == Backend::RayQuery),
      lookup_(setup.cacheLookups),
      lightPoints_(setup.emitterGraphs),
      tracedInputs_(setup.materials && setup.materials->tracedInputs),
      ambientOcclusionIntegrator_(setup.ambientOcclusionIntegrator),
      pixels_(width * height) {
  VkDevice device = context.device();
  const LinkedMaterials* materials = setup.materials;
  const std::uint32_t pathSlots = setup.pathSlots;
  // The renderer refuses both first, in the user's words (trace/shading.cpp, wavefrontGap).
  if (((lookup_ || lightPoints_) && !materials) || (!query_ && !context.info().traceRaysIndirect) ||
      (ambientOcclusionIntegrator_ && (materials || setup.sharedPrimaryHits)))
    throw std::logic_error(
        "WavefrontPathTracer: a cache or emitters' graphs without material passes, a "
        "pipeline without indirect trace launches, or the AO integrator with materials or "
        "shared camera hits");
  // The path state (vec4 fields a slot, four more for material outputs, one more for the
  // path state that Light Path reads, two more for light samples' points), the queues (two
  // live, one shadow, with materials the material-sorted one; a uint a slot) and the control
  // block (with a record a material bin); each bound whole, so each must fit a storage
  // binding. Bins are distinct graphs: materials sharing a graph share its pipeline.
  const std::uint32_t bins = materials ? static_cast<std::uint32_t>(materials->distinct.size()) : 0;
  // With --shared-primary two more after the others keep the camera ray's hit for the later
  // rounds (wavefront.glsl, MG_WAVEFRONT_PRIMARY_FIELD).
  // With BSDF lobes, their fields come before those (MG_WAVEFRONT_LOBE_FIELD).
  const std::uint32_t fieldsBeforeLobes =
      !materials ? gpu::kPathStateFields
                 : gpu::kPathStateFieldsWithMaterials +
                       (materials->pathInputs ? gpu::kPathStateFieldsForPathInputs : 0u) +
                       (lightPoints_ ? gpu::kPathStateFieldsForLightPoints : 0u);
  const bool lobes = materials && materials->bsdfLobes;
  // With traced inputs one more after the lobes' (MG_WAVEFRONT_TRACED_FIELD).
  const std::uint32_t fieldsBeforeTraced =
      fieldsBeforeLobes + (lobes ? gpu::kPathStateFieldsForLobes : 0u);
  const std::uint32_t fieldsBeforePrimary =
      fieldsBeforeTraced + (tracedInputs_ ? gpu::kPathStateFieldsForTracedInputs : 0u);
  const std::uint32_t fieldsBeforeMinRayPdf =
      fieldsBeforePrimary + (setup.sharedPrimaryHits ? 2u : 0u);
  const std::uint32_t fieldsBeforeCut =
      fieldsBeforeMinRayPdf + (setup.minRayPdf ? gpu::kPathStateFieldsForMinRayPdf : 0u);
  // With cut values for the shade pass, the widest cut's floats after those, four a field.
  const std::uint32_t cutFields =
      materials && setup.cutValuesToShade ? (materials->cutValueCount + 3) / 4 : 0u;
  const std::uint32_t fields = fieldsBeforeCut + cutFields;
  // Paths in flight: as asked, else every pixel, or as many as one storage binding of path
  // state, a row of work groups and the largest allocation hold (lavapipe's 128 MiB range:
  // about 645,000 with graphs, so a 1080p round there runs in 4 chunks).
  const DeviceInfo& info = context.info();
  std::uint64_t fitted =
      std::uint64_t(info.limits.maxComputeWorkGroupCount[0]) * gpu::kWavefrontWorkgroupSize;
  for (std::uint64_t limit : {std::uint64_t(info.limits.maxStorageBufferRange),
                              std::uint64_t(info.maxMemoryAllocationSize)})
    if (limit > 0)
      fitted = std::min(fitted, limit / (std::uint64_t(fields) * 16));
  slots_ = pathSlots > 0 ? std::min(pathSlots, pixels_)
                         : static_cast<std::uint32_t>(std::min<std::uint64_t>(pixels_, fitted));
  if (slots_ == 0)
    throw std::invalid_argument("--shading wavefront: the device holds no path state");
  chunks_ = (pixels_ + slots_ - 1) / slots_;
  if (workgroupsFor(slots_) > info.limits.maxComputeWorkGroupCount[0])
    throw std::invalid_argument("--wavefront-paths " + std::to_string(slots_) +
                                " needs more compute work groups in a row than " + info.name +
                                " has; ask for fewer");
  const std::uint64_t stateBytes = std::uint64_t(slots_) * fields * 16;
  checkBufferSize(context, stateBytes,
                  "--wavefront-paths " + std::to_string(slots_) + ": the path state (" +
                      std::to_string(fields) + " x 16 bytes a path)",
                  true);
  pathState_ = GpuBuffer(context, stateBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  // With the tile cache the queued tiles' sorted list follows the four queues.
  const std::uint64_t queueWords =
      std::uint64_t(slots_) * (materials ? 4 : 3) + (materials ? setup.tileQueueCapacity : 0);
  checkBufferSize(context, queueWords * sizeof(std::uint32_t), "--shading wavefront's queues",
                  true);
  pathQueues_ = GpuBuffer(context, queueWords * sizeof(std::uint32_t),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  control_ = GpuBuffer(context, sizeof(gpu::WavefrontControl) + bins * kBinRecordBytes,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);

  if (bins > 0)
    binReadback_ = hostBuffer(context, bins * kBinRecordBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  std::vector<MaterialShaderUnit> passUnits;
  if (materials)
    passUnits = planMaterialPasses(*materials, setup.materialInstances);
  VkShaderStageFlags stages = query_ ? VK_SHADER_STAGE_COMPUTE_BIT
                                     : VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_RAYGEN_BIT_KHR;
  setLayout_ = createTraceSetLayout(device, stages, textureCount, setup.tileImage, true);
  layout_ = createPipelineLayout(device, setLayout_.get(), stages, pushBytes_);

  std::vector<std::string> defines = {"MG_TEXTURE_COUNT=" + std::to_string(textureCount),
                                      query_ ? "MG_BACKEND_QUERY=1" : "MG_BACKEND_PIPELINE=1"};
  defines.insert(defines.end(), extraDefines.begin(), extraDefines.end());
  if (setup.sharedPrimaryHits)
    defines.push_back("MG_WAVEFRONT_PRIMARY_FIELD=" + std::to_string(fieldsBeforePrimary));
  if (lobes)
    defines.push_back("MG_WAVEFRONT_LOBE_FIELD=" + std::to_string(fieldsBeforeLobes));
  if (setup.minRayPdf)
    defines.push_back("MG_WAVEFRONT_MIN_RAY_PDF_FIELD=" + std::to_string(fieldsBeforeMinRayPdf));
  if (cutFields > 0) {
    defines.push_back("MG_WAVEFRONT_CUT_FIELD=" + std::to_string(fieldsBeforeCut));
    defines.push_back("MG_WAVEFRONT_CUT_FIELDS=" + std::to_string(cutFields));
  }
  if (tracedInputs_) {
    defines.push_back("MG_WAVEFRONT_TRACED_FIELD=" + std::to_string(fieldsBeforeTraced));
    // Per bin, whether its graph reads a traced input: those bins' hits go first in the
    // material-sorted queue, the traced-inputs pass's range.
    std::vector<bool> traced(bins, false);
    for (const LinkedMaterial& material : materials->materials)
      if (material.ambientOcclusionSamples > 0 || material.bevelSamples > 0)
        traced[material.distinctIndex] = true;
    std::string binTraced = "bool[](";
    for (std::uint32_t bin = 0; bin < bins; ++bin)
      binTraced += std::string(bin ? ", " : "") + (traced[bin] ? "true" : "false");
    defines.push_back("MG_MATERIAL_BIN_TRACED=" + binTraced + ")");
  }
  if (materials) {
    // Scene material id -> bin (its distinct graph), for the binning passes' lookup.
    std::string binOf = "uint[](";
    for (std::size_t i = 0; i < materials->materials.size(); ++i)
      binOf += (i ? ", " : "") + std::to_string(materials->materials[i].distinctIndex) + "u";
    defines.push_back("MG_MATERIAL_COUNT=" + std::to_string(materials->materials.size()));
    defines.push_back("MG_MATERIAL_BIN_COUNT=" + std::to_string(bins));
    defines.push_back("MG_MATERIAL_BIN_OF=" + binOf + ")");
  }
  const bool computeSubgroups =
      (context.info().subgroupArithmeticStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0;
  // Every shader's SPIR-V first, then every pipeline at once (createPipelines). The compute
  // passes' and the ray-tracing pipeline's shaders compile together on the threads (the five
  // ray-tracing shaders compiled one after another added their sum to a cold start), then
  // the material passes'.
  WavefrontPipelineChoice choice;
  choice.rayQuery = query_;
  choice.materialPasses = static_cast<std::uint32_t>(binsOfPass_.size());
  choice.cacheLookups = lookup_;
  choice.tracedInputs = tracedInputs_;
  choice.ambientOcclusionIntegrator = ambientOcclusionIntegrator_;
  PipelineShaders shaders;
  shaders.passes = wavefrontComputePasses(choice);
  std::vector<ShaderCompileRequest> requests;
  for (std::uint32_t pass : shaders.passes) {
    std::vector<std::string> passDefines = defines;
    passDefines.push_back(kPassDefines[pass]);
    if (computeSubgroups)
      passDefines.push_back("MG_SUBGROUP_RAY_COUNT=1");
    requests.push_back({"wavefront.glsl", ShaderStage::Compute, std::move(passDefines)});
  }
  if (!query_)
    appendRayTracingRequests(defines, tracedInputs_ || ambientOcclusionIntegrator_, requests,
                             shaders.rayTracingStages);
  std::vector<std::vector<std::uint32_t>> spirv =
      compiler.compileAll(requests, setup.compileThreads);
  for (std::size_t i = 0; i < spirv.size(); ++i) {
    if (i < shaders.passes.size())
      shaders.passSpirv.push_back(std::move(spirv[i]));
    else
      shaders.rayTracingModules.push_back(createShaderModule(device, spirv[i]));
  }
  if (materials)
    shaders.materialSpirv =
        compileMaterialPasses(compiler, *materials, passUnits, binsOfPass_, defines, setup);
  for (std::size_t pass = 0; pass < shaders.materialSpirv.size(); ++pass)
    materialPassSizes_.push_back(
        {spirvSize(shaders.materialSpirv[pass]),
         spirvFunctionCopies(shaders.materialSpirv[pass],
                             "EvaluateMaterial_" + materialPassNames_[pass])});
  createPipelines(shaders, setup.compileThreads);
  const bool sharesAPass =
      std::any_of(binInstances_.begin(), binInstances_.end(),
                  [](const std::vector<std::uint32_t>& words) { return !words.empty(); });
  if (materials && setup.ownPassesFromSecondFrame && sharesAPass)
    deferredOwnPasses_ = DeferredOwnPasses{compiler.fresh(), defines, setup};
}

// Each graph of a shared pass gets a pass of its own, compiled and created now (on the
// set-up's threads, longest first), and the shared pass goes: frames from here on bind them.
// A graph's own pass from the set-up stays as it is. The frame before has completed (the
// frame loop submits and waits), so no command buffer still holds a shared pipeline.
std::uint32_t WavefrontPathTracer::createDeferredPipelines() {
  if (!deferredOwnPasses_)
    return 0;
  const DeferredOwnPasses deferred = std::move(*deferredOwnPasses_);
  deferredOwnPasses_.reset();
  const LinkedMaterials& materials = *deferred.setup.materials;
  std::vector<VulkanHandle<VkPipeline>> pipelines;
  std::vector<std::vector<std::uint32_t>> binsOfPass;
  std::vector<std::string> names;
  std::vector<MaterialPassSize> sizes;
  std::vector<MaterialShaderUnit> units;
  std::vector<std::size_t> passOfUnit;
  for (std::size_t pass = 0; pass < materialPasses_.size(); ++pass) {
    const std::vector<std::uint32_t>& bins = binsOfPass_[pass];
    if (binInstances_[bins.front()].empty()) {  // a graph's own pass already
      pipelines.push_back(std::move(materialPasses_[pass]));
      binsOfPass.push_back(bins);
      names.push_back(materialPassNames_[pass]);
      sizes.push_back(materialPassSizes_[pass]);
      continue;
    }
    for (const std::uint32_t bin : bins) {
      units.push_back({nullptr, bin});
      passOfUnit.push_back(pipelines.size());
      pipelines.emplace_back();
      binsOfPass.push_back({bin});
      names.push_back(materials.distinct[bin].name);
      sizes.emplace_back();
      binInstances_[bin].clear();  // its pass reads no parameter block
    }
  }
  std::vector<std::vector<std::uint32_t>> binsOfUnit;
  for (const std::size_t pass : passOfUnit)
    binsOfUnit.push_back(binsOfPass[pass]);
  ShaderCompiler compiler = deferred.compiler.fresh();
  const std::vector<std::vector<std::uint32_t>> spirv = compileMaterialPasses(
      compiler, materials, units, binsOfUnit, deferred.defines, deferred.setup);
  std::vector<std::size_t> unitsBySize(units.size());
  for (std::size_t unit = 0; unit < units.size(); ++unit)
    unitsBySize[unit] = unit;
  std::stable_sort(unitsBySize.begin(), unitsBySize.end(),
                   [&](std::size_t a, std::size_t b) { return spirv[a].size() > spirv[b].size(); });
  const std::uint32_t threads = deferred.setup.compileThreads;
  ThreadPipelineCaches caches(context_.pipelineCache(), workerThreads(threads, units.size()));
  parallelFor(units.size(), threads, [&](std::size_t job, std::uint32_t thread) {
    const std::size_t unit = unitsBySize[job];
    const std::size_t pass = passOfUnit[unit];
    auto module = createShaderModule(context_.device(), spirv[unit]);
    pipelines[pass] = createComputePipeline(context_, module.get(), layout_.get(),
                                            ("wavefront material " + names[pass]).c_str(),
                                            caches.forThread(thread));
  });
  caches.merge();
  for (std::size_t unit = 0; unit < units.size(); ++unit)
    sizes[passOfUnit[unit]] = {
        spirvSize(spirv[unit]),
        spirvFunctionCopies(spirv[unit], "EvaluateMaterial_" + names[passOfUnit[unit]])};
  materialPasses_ = std::move(pipelines);
  binsOfPass_ = std::move(binsOfPass);
  materialPassNames_ = std::move(names);
  materialPassSizes_ = std::move(sizes);
  return static_cast<std::uint32_t>(units.size());
}

// The material passes (binsOfPass_ and the units to compile): an instance group's shared pass
// where its parameters fit the push constants, else a pass per graph; the push range's size.
std::vector<MaterialShaderUnit> WavefrontPathTracer::planMaterialPasses(
    const LinkedMaterials& materials, bool instances) {
  const std::uint32_t pushLimit = context_.info().limits.maxPushConstantsSize;
  const std::uint32_t capacity =
      pushLimit > gpu::kMaterialParameterPushOffset
          ? (pushLimit - gpu::kMaterialParameterPushOffset) / sizeof(float)
          : 0u;
  std::vector<MaterialShaderUnit> units;
  materialBins_ = static_cast<std::uint32_t>(materials.distinct.size());
  binInstances_.assign(materialBins_, {});
  for (const MaterialInstanceGroup& group : materials.instanceGroups) {
    const InstanceGroup& shared = group.instances;
    if (instances && shared.members.size() > 1 && shared.parameterCount <= capacity) {
      units.push_back({&group, 0});
      binsOfPass_.push_back(shared.members);
      materialPassNames_.push_back(group.name);
      // Each bin's words after the WavefrontPush: an ivec4 (x its first texture slot), then
      // its parameters as float bits.
      for (std::size_t m = 0; m < shared.members.size(); ++m) {
        std::vector<std::uint32_t>& words = binInstances_[shared.members[m]];
        words.assign(4, 0u);
        words[0] = static_cast<std::uint32_t>(materials.distinct[shared.members[m]].textureBase);
        for (std::uint32_t k = 0; k < shared.parameterCount; ++k)
          words.push_back(
              std::bit_cast<std::uint32_t>(shared.parameters[m * shared.parameterCount + k]));
      }
      pushBytes_ = std::max<std::uint32_t>(
          pushBytes_, gpu::kMaterialParameterPushOffset + shared.parameterCount * sizeof(float));
      continue;
    }
    for (const std::uint32_t bin : shared.members) {
      units.push_back({nullptr, bin});
      binsOfPass_.push_back({bin});
      materialPassNames_.push_back(materials.distinct[bin].name);
    }
  }
  return units;
}

// One small shader per material pass (an instance group's, or a graph's:
// material_instances.h), compiled with only that include (as a material callable is), so no
// compile ever sees all of a scene's graphs: the query backend's megakernel inlines every one
// (the classroom's 88 do not compile on lavapipe). Compiled on several threads (glslang took
// 4.4 s for all of the classroom's 88 graphs, cold, one pass each).
std::vector<std::vector<std::uint32_t>> WavefrontPathTracer::compileMaterialPasses(
    ShaderCompiler& compiler, const LinkedMaterials& materials,
    const std::vector<MaterialShaderUnit>& units,
    const std::vector<std::vector<std::uint32_t>>& binsOfUnit,
    const std::vector<std::string>& defines, const WavefrontSetup& setup) {
  MaterialShaderRequest request;
  request.cutFunctions = setup.cutKeys;
  request.source = "wavefront.glsl";
  request.stage = ShaderStage::Compute;
  request.defines = defines;
  request.defines.push_back(kPassDefines[gpu::kWavefrontMaterial]);
  request.units = units;
  // The evaluation of light points only in the passes of graphs that emitters' light samples
  // evaluate: the others' bins never hold a point, and each pass compiled is a driver's
  // compile at a cold start.
  // With cut values for the shade pass, a graph whose rest the shade pass runs hands it its
  // cut's values (its pass runs the rest only for light points). A pass's graphs share one
  // shape, so they agree.
  request.materialDefines.resize(binsOfUnit.size());
  for (std::size_t pass = 0; pass < binsOfUnit.size(); ++pass) {
    const auto& bins = binsOfUnit[pass];
    if (lightPoints_ && std::any_of(bins.begin(), bins.end(), [&](std::uint32_t bin) {
          return setup.lightPointGraphs.empty() ||
                 (bin < setup.lightPointGraphs.size() && setup.lightPointGraphs[bin]);
        }))
      request.materialDefines[pass].push_back("MG_MATERIAL_LIGHT_POINTS=1");
    if (setup.cutValuesToShade && !bins.empty() && materials.distinct[bins.front()].restInShade)
      request.materialDefines[pass].push_back("MG_MATERIAL_REST_IN_SHADE=1");
  }
  request.threads = setup.compileThreads;
  request.what = "wavefront material pass";
  return compileMaterialShaders(compiler, materials, request, materialShaderStats_);
}

// The ray-tracing pipeline's shaders, as compile requests: the trace and shadow raygens (and
// with `tracesFromHits` the traced-inputs raygen: traced inputs or the AO integrator's rays),
// then the megakernel's miss and hit shaders (they only report the hit).
void WavefrontPathTracer::appendRayTracingRequests(const std::vector<std::string>& defines,
                                                   bool tracesFromHits,
                                                   std::vector<ShaderCompileRequest>& requests,
                                                   std::vector<VkShaderStageFlagBits>& stages) {
  std::vector<std::uint32_t> raygens = {gpu::kWavefrontTrace, gpu::kWavefrontShadow};
  if (tracesFromHits)
    raygens.push_back(gpu::kWavefrontTracedInputs);
  for (std::uint32_t pass : raygens) {
    std::vector<std::string> raygenDefines = defines;
    raygenDefines.push_back(kPassDefines[pass]);
    requests.push_back({"wavefront.glsl", ShaderStage::RayGen, std::move(raygenDefines)});
    stages.push_back(VK_SHADER_STAGE_RAYGEN_BIT_KHR);
  }
  appendReportingShaderRequests(requests, stages);
}

// The pipelines are independent, and the driver compiles each on the thread that creates
// it: creating them one after another left all but one core idle (on lavapipe the
// classroom's material pipelines took 33.9 s on one thread and 17.5 s on this 2-core
// machine's two). So every pipeline is one job of a parallelFor; each job writes its own
// slot, so the result does not depend on the order they finish in. The pipeline cache they
// share is internally synchronised; on a cold start each thread has a cache of its own
// instead (ThreadPipelineCaches: no driver lock shared between the threads), merged into the
// device's once every pipeline exists. The jobs go longest first (a greedy schedule's last job
// to start then is a short one, so no core runs on alone at the end): the ray-tracing
// pipeline (five shaders), then the material passes by their SPIR-V's size, the largest
// first (a driver's compile grows with the code), then the small compute passes.
void WavefrontPathTracer::createPipelines(const PipelineShaders& shaders, std::uint32_t threads) {
  VkDevice device = context_.device();
  computePasses_.resize(gpu::kWavefrontPassCount);
  materialPasses_.resize(shaders.materialSpirv.size());
  std::vector<std::size_t> passesBySize(shaders.materialSpirv.size());
  for (std::size_t pass = 0; pass < passesBySize.size(); ++pass)
    passesBySize[pass] = pass;
  std::stable_sort(passesBySize.begin(), passesBySize.end(), [&](std::size_t a, std::size_t b) {
    return shaders.materialSpirv[a].size() > shaders.materialSpirv[b].size();
  });
  const std::size_t rayTracingJobs = shaders.rayTracingModules.empty() ? 0 : 1;
  const std::size_t jobs = rayTracingJobs + shaders.materialSpirv.size() + shaders.passes.size();
  ThreadPipelineCaches caches(context_.pipelineCache(), workerThreads(threads, jobs));
  parallelFor(jobs, threads, [&](std::size_t job, std::uint32_t thread) {
    if (job < rayTracingJobs) {
      std::vector<VkShaderModule> moduleHandles;
      for (const auto& module : shaders.rayTracingModules)
        moduleHandles.push_back(module.get());
      rayTracing_ = createRayTracingPipeline(context_, moduleHandles, shaders.rayTracingStages,
                                             layout_.get(), 1, false, "wavefront ray tracing");
      return;
    }
    job -= rayTracingJobs;
    if (job < passesBySize.size()) {
      const std::size_t pass = passesBySize[job];
      auto module = createShaderModule(device, shaders.materialSpirv[pass]);
      materialPasses_[pass] = createComputePipeline(
          context_, module.get(), layout_.get(),
          ("wavefront material " + materialPassNames_[pass]).c_str(), caches.forThread(thread));
      return;
    }
    job -= passesBySize.size();
    const std::uint32_t pass = shaders.passes[job];
    auto module = createShaderModule(device, shaders.passSpirv[job]);
    computePasses_[pass] = createComputePipeline(context_, module.get(), layout_.get(),
                                                 kPassNames[pass], caches.forThread(thread));
  });
  caches.merge();
  if (rayTracingJobs == 0)
    return;
  // The table: [trace raygen][shadow raygen]([traced-inputs raygen])[miss, shadow miss][hit];
  // the pipeline keeps the spec's default stack.
  const bool tracesFromHits = tracedInputs_ || ambientOcclusionIntegrator_;
  const std::uint32_t raygens = tracesFromHits ? 3 : 2;
  std::vector<ShaderBindingRegion> regions;
  for (std::uint32_t raygen = 0; raygen < raygens; ++raygen)
    regions.push_back({{raygen}, true});
  regions.push_back({{raygens, raygens + 1}});
  regions.push_back({{raygens + 2}});
  ShaderBindingTable table =
      createShaderBindingTable(context_, rayTracing_.get(), raygens + 3, regions);
  shaderBindingTable_ = std::move(table.buffer);
  traceRaygenRegion_ = table.regions[0];
  shadowRaygenRegion_ = table.regions[1];
  if (tracesFromHits)
    tracedInputsRaygenRegion_ = table.regions[2];
  missRegion_ = table.regions[raygens];
  hitRegion_ = table.regions[raygens + 1];
}

std::uint32_t WavefrontPathTracer::timestampCount(std::uint32_t paths,
                                                  std::uint32_t bounces) const {
  return 1 + static_cast<std::uint32_t>(framePasses(paths, bounces, pixels_).size());
}

void WavefrontPathTracer::recordPass(VkCommandBuffer commands, std::uint32_t pass,
                                     std::uint32_t pixels, std::uint32_t chunk, std::uint32_t round,
                                     std::uint32_t bounce, bool countsHits,
                                     bool lightPoints) const {
  // Live queues alternate: bounce b traces queue b % 2 and appends to the other.
  gpu::WavefrontPush push{};
  push.step = glm::uvec4(round, bounce, bounce % 2, 0);
  const std::uint32_t firstPixel = chunk * slots_;
  const std::uint32_t chunkPixels = std::min(slots_, pixels - firstPixel);
  // w: LiPaC's counting frame (the trace pass counts its rays, hit_feedback.glsl); the
  // light samples' points binned and evaluated after the shadow pass.
  push.chunk = glm::uvec4(slots_, firstPixel, chunkPixels,
                          (countsHits ? gpu::kWavefrontCountsHits : 0u) |
                              (lightPoints ? gpu::kWavefrontLightPoints : 0u));
  VkShaderStageFlags stages = query_ ? VK_SHADER_STAGE_COMPUTE_BIT
                                     : VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_RAYGEN_BIT_KHR;
  vkCmdPushConstants(commands, layout_.get(), stages, 0, sizeof push, &push);
  const bool traces = pass == gpu::kWavefrontTrace || pass == gpu::kWavefrontShadow ||
                      pass == gpu::kWavefrontTracedInputs;
  if (traces && !query_) {
    // The launch size is the queue's count, written by the pass before (generate or queue),
    // or for the traced inputs the bin offsets pass's count of their hits.
    std::size_t launchOffset = offsetof(gpu::WavefrontControl, liveLaunch);
    const VkStridedDeviceAddressRegionKHR* raygen = &traceRaygenRegion_;
    if (pass == gpu::kWavefrontShadow) {
      launchOffset = offsetof(gpu::WavefrontControl, shadowLaunch);
      raygen = &shadowRaygenRegion_;
    } else if (pass == gpu::kWavefrontTracedInputs) {
      // The AO integrator's pass runs over the live queue, the traced inputs' over their hits.
      if (!ambientOcclusionIntegrator_)
        launchOffset = offsetof(gpu::WavefrontControl, tracedLaunch);
      raygen = &tracedInputsRaygenRegion_;
    }
    const VkStridedDeviceAddressRegionKHR callables{};
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, rayTracing_.get());
    context_.functions().cmdTraceRaysIndirect(commands, raygen, &missRegion_, &hitRegion_,
                                              &callables, control_.address() + launchOffset);
    return;
  }
  if (pass == gpu::kWavefrontMaterial) {
    // Every bin's graph over its batch, each sized by the offsets pass; the bins' slots are
    // disjoint, so no barrier between them. The bins of an instance group share a pipeline.
    // A shared pass takes each bin's graph (its texture slot and parameters) after the
    // WavefrontPush (shared_types.h, kMaterialParameterPushOffset).
    for (std::size_t material = 0; material < materialPasses_.size(); ++material) {
      vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, materialPasses_[material].get());
      for (const std::uint32_t bin : binsOfPass_[material]) {
        push.step.w = bin;
        vkCmdPushConstants(commands, layout_.get(), stages, 0, sizeof push, &push);
        const std::vector<std::uint32_t>& instance = binInstances_[bin];
        if (!instance.empty())
          vkCmdPushConstants(commands, layout_.get(), stages, sizeof push,
                             static_cast<std::uint32_t>(instance.size() * sizeof(std::uint32_t)),
                             instance.data());
        vkCmdDispatchIndirect(commands, control_.buffer(),
                              sizeof(gpu::WavefrontControl) + bin * kBinRecordBytes);
      }
    }
    return;
  }
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, computePasses_[pass].get());
  switch (pass) {
    case gpu::kWavefrontGenerate:
    case gpu::kWavefrontFinish:
      vkCmdDispatch(commands, workgroupsFor(chunkPixels), 1, 1);
      break;
    case gpu::kWavefrontQueue:
    case gpu::kWavefrontBinOffsets:
      vkCmdDispatch(commands, 1, 1, 1);
      break;
    case gpu::kWavefrontShadow:
      vkCmdDispatchIndirect(commands, control_.buffer(),
                            offsetof(gpu::WavefrontControl, shadowGroups));
      break;
    case gpu::kWavefrontTracedInputs:
      vkCmdDispatchIndirect(commands, control_.buffer(),
                            ambientOcclusionIntegrator_
                                ? offsetof(gpu::WavefrontControl, liveGroups)
                                : offsetof(gpu::WavefrontControl, tracedGroups));
      break;
    case gpu::kWavefrontBinCount:
    case gpu::kWavefrontBinScatter:
      // The light points are some of the shadow rays: their groups cover them.
      vkCmdDispatchIndirect(commands, control_.buffer(),
                            lightPoints ? offsetof(gpu::WavefrontControl, shadowGroups)
                                        : offsetof(gpu::WavefrontControl, liveGroups));
      break;
    default:  // trace, shade, bin count and scatter: over the live queue
      vkCmdDispatchIndirect(commands, control_.buffer(),
                            offsetof(gpu::WavefrontControl, liveGroups));
      break;
  }
}

void WavefrontPathTracer::record(VkCommandBuffer commands, VkDescriptorSet set, std::uint32_t paths,
                                 std::uint32_t bounces, bool countsHits, VkQueryPool timestamps,
                                 std::uint32_t firstQuery, std::uint32_t pixels) const {
  if (pixels == 0 || pixels > pixels_)
    pixels = pixels_;
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set, 0,
                          nullptr);
  if (!query_)
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, layout_.get(), 0, 1,
                            &set, 0, nullptr);
  const bool materials = !materialPasses_.empty();
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  if (materials) {
    // The bins' counters and frame sums start from 0.
    vkCmdFillBuffer(commands, control_.buffer(), 0, VK_WHOLE_SIZE, 0);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
  }
  std::uint32_t query = firstQuery;
  if (timestamps)
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, query++);
  // Every pass reads what the one before wrote, the indirect ones their arguments too.
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask =
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  std::uint32_t chunk = 0, round = 0, bounce = 0;
  for (const FramePass& step : framePasses(paths, bounces, pixels)) {
    recordPass(commands, step.pass, pixels, chunk, round, bounce, countsHits, step.lightPoints);
    if (timestamps)
      vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, query++);
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    // A bounce ends with its shadow pass, or with the material passes of its light points.
    if ((step.pass == gpu::kWavefrontShadow && !lightPoints_) ||
        (step.pass == gpu::kWavefrontMaterial && step.lightPoints))
      ++bounce;
    if (step.pass == gpu::kWavefrontFinish) {
      bounce = 0;
      if (++round == paths) {
        round = 0;
        ++chunk;
      }
    }
  }
  if (materials) {
    // The last pass's barrier made its writes visible to shaders; the copy is a transfer.
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    VkBufferCopy copy{sizeof(gpu::WavefrontControl), 0,
                      std::size_t{materialBins_} * kBinRecordBytes};
    vkCmdCopyBuffer(commands, control_.buffer(), binReadback_.buffer(), 1, &copy);
  }
}

std::vector<std::uint32_t> WavefrontPathTracer::binHits() const {
  std::vector<std::uint32_t> hits;
  if (materialPasses_.empty())
    return hits;
  constexpr std::size_t kRecords = kBinRecordBytes / sizeof(glm::uvec4);
  std::vector<glm::uvec4> records(std::size_t{materialBins_} * kRecords);
  binReadback_.read(records.data(), records.size() * sizeof(glm::uvec4));
  for (std::size_t bin = 0; bin < materialBins_; ++bin)
    hits.push_back(records[kRecords * bin].w);
  return hits;
}

void WavefrontPathTracer::addPassTimes(const std::vector<std::uint64_t>& ticks, std::uint32_t paths,
                                       std::uint32_t bounces, double millisecondsPerTick,
                                       FrameStats& frame) const {
  const auto passes = framePasses(paths, bounces, pixels_);
  if (ticks.size() < passes.size() + 1)
    return;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const double ms = double(ticks[i + 1] - ticks[i]) * millisecondsPerTick;
    frame.*kPassTimes[passes[i].pass] += ms;
  }
}

void WavefrontPathTracer::addResources(TraceResources& resources) const {
  resources.pathState = &pathState_;
  resources.pathQueues = &pathQueues_;
  resources.wavefrontControl = &control_;
}

void WavefrontPathTracer::addFrameStats(const FrameTrace& trace,
                                        const std::vector<std::uint64_t>* passTicks,
                                        double millisecondsPerTick, FrameStats& stats) const {
  stats.wavefrontBinHits = binHits();
  if (passTicks)
    addPassTimes(*passTicks, trace.paths, trace.rays, millisecondsPerTick, stats);
}

}  // namespace memograph::runtime
