#include "runtime/trace/render_pipelines.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <optional>
#include <string>
#include <thread>

#include "runtime/materials/material_callables.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/megakernel/megakernel_tracer.h"
#include "runtime/trace/wavefront/wavefront_path_tracer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"

namespace memograph::runtime {

namespace {

// What the stages below share.
struct ShaderBuild {
  const VulkanContext& context;
  const RendererOptions& options;
  const RenderSettings& settings;
  const RenderPlan& plan;
  const PipelineInputs& inputs;
  bool floor = false;  // the floor run compiles no graph: the prelude and no callables
  // MaterialInputs without the object-space members when no graph reads them: the callable
  // payload and the raygen's stack shrink (on the H200 the classroom's texel row: 144.7 ms
  // and a 896 B stack with them, 128.5 ms and 576 B without).
  bool omitObjectInputs = false;
  // Likewise without the path state when no graph reads it (Light Path): the path tracer
  // then tracks none, so such scenes trace as before it existed.
  bool omitPathInputs = false;
  // Likewise without the traced inputs (Ambient Occlusion) when no graph reads them: the
  // megakernel then traces no rays for them.
  bool omitTracedInputs = false;
  // Likewise MaterialOutputs without the BSDF lobes when no graph writes them
  // (MG_OMIT_BSDF_LOBES): the callable payload keeps its size and the tracer its BRDF alone.
  bool omitBsdfLobes = false;
  // The texel cache keys materials by their cut (MG_CACHE_CUTS, texel_cache.glsl): see
  // cutKeys.
  bool cutKeys = false;
};

// Whether the texel cache keys the materials that are not cacheable as a whole by their cut
// (uv texels, object-space or world-space voxels) in this render: in the megakernel's switch
// dispatch, whose one shader holds every material's cut and rest functions (materials.glsl),
// and in the wavefront, whose lookup pass reads a cut's values and whose material passes
// (one graph each) evaluate the cut on a miss and the rest always. The callable dispatch
// would need each material's callable to run its cut and rest apart: it keeps the
// whole-material uv cache. The tile cache keeps it too: a tile is a square of texels of a 2D
// parameterisation of the surface (uv), which a voxel key has none of; filling a tile around
// a hit from its derivatives (the thesis's extrapolation, §5.4.3) for other domains is not
// done.
bool keysCuts(const RenderPlan& plan, bool callables, bool floor, const LinkedMaterials& m) {
  return plan.cache.mode == CacheMode::Texel && !callables && !floor && m.cutValueCount > 0;
}

// The pipeline backend's callable material shaders, one per distinct material.
MaterialCallables compileCallables(const ShaderBuild& b,
                                   const std::map<std::string, std::string>& files,
                                   ShaderCacheStats& callableStats) {
  MaterialCallableCompileOptions callableOptions;
  if (b.omitObjectInputs)
    callableOptions.defines.push_back("MG_OMIT_OBJECT_INPUTS=1");
  if (b.omitPathInputs)
    callableOptions.defines.push_back("MG_OMIT_PATH_INPUTS=1");
  if (b.omitTracedInputs)
    callableOptions.defines.push_back("MG_OMIT_TRACED_INPUTS=1");
  if (b.omitBsdfLobes)
    callableOptions.defines.push_back("MG_OMIT_BSDF_LOBES=1");
  else if (b.inputs.materials->linked.closureChoice)
    callableOptions.defines.push_back("MG_CLOSURE_CHOICE=1");
  callableOptions.files = files;
  callableOptions.cacheDirectory = b.inputs.shaderCacheDirectory;
  callableOptions.textureCount = b.inputs.scene->textures->count();
  callableOptions.threads = b.options.shaderCompileThreads;
  return compileMaterialCallables(b.inputs.materials->linked, callableOptions, callableStats);
}

// Whether the path tracer blurs glossy lobes by Cycles' Filter Glossy: a path-traced render
// with F > 0 (the AO integrator shades no BSDF).
bool filterGlossyOn(const ShaderBuild& b) {
  return b.inputs.filterGlossy > 0.0f && b.options.integrator == Integrator::Path;
}

// The path tracer's defines besides the backend's: the cache's, then the scene's.
std::vector<std::string> pathTracerDefines(const ShaderBuild& b, const MaterialCache& cache) {
  std::vector<std::string> defines = cache.defines();
  if (b.floor)
    defines.push_back("MG_MATERIAL_FLOOR=1");
  if (b.options.integrator == Integrator::AmbientOcclusion)
    for (std::string& define : ambientOcclusionDefines(b.options.ambientOcclusion.samples,
                                                       b.inputs.ambientOcclusionDistance))
      defines.push_back(std::move(define));
  if (b.omitObjectInputs)
    defines.push_back("MG_OMIT_OBJECT_INPUTS=1");
  if (b.omitPathInputs)
    defines.push_back("MG_OMIT_PATH_INPUTS=1");
  if (b.omitTracedInputs)
    defines.push_back("MG_OMIT_TRACED_INPUTS=1");
  if (b.cutKeys)
    defines.push_back("MG_CACHE_CUTS=1");
  if (b.options.debugCacheMisses)
    defines.push_back("MG_DEBUG_CACHE_MISSES=1");
  // Cycles' Principled weighting, only for scenes whose materials write it (brdf.glsl).
  if (b.inputs.materials->linked.cyclesPrincipled && !b.floor)
    defines.push_back("MG_CYCLES_PRINCIPLED=1");
  // BSDF lobes (Diffuse, Glossy, Velvet BSDF, Mix Shader), only for scenes whose materials
  // write them (bsdf_lobes.glsl); the others' MaterialOutputs carry none.
  defines.push_back(b.omitBsdfLobes ? "MG_OMIT_BSDF_LOBES=1" : "MG_BSDF_LOBES=1");
  if (!b.omitBsdfLobes && b.inputs.materials->linked.principledLayers)
    defines.push_back("MG_PRINCIPLED_LAYERS=1");
  if (!b.omitBsdfLobes && b.inputs.materials->linked.closureChoice)
    defines.push_back("MG_CLOSURE_CHOICE=1");
  if (!b.omitBsdfLobes && b.inputs.materials->linked.lobeNormals)
    defines.push_back("MG_LOBE_NORMALS=1");
  // Emissive-triangle NEE and its MIS, only for scenes with emissive triangles; with free
  // materials too, so the floor traces the same rays. NEE evaluates emitters whose emission
  // is not a known constant: a second material call site, compiled only for scenes that
  // have such emitters (path_tracer.glsl).
  if (b.inputs.scene->buffers.emissiveTriangles)
    defines.push_back("MG_EMISSIVE_NEE=1");
  if (b.inputs.materials->neeEvaluatesEmission && !b.floor)
    defines.push_back("MG_NEE_EVALUATES_EMISSION=1");
  // Shadow rays through Transparent lobes and opacities below 1 (transparent_shadow.glsl),
  // only for scenes with a material that may be transparent; the others keep their opaque
  // shadow rays and kernels. The floor evaluates no graph, so its shadows stay opaque.
  if (!b.floor && b.inputs.materials->linked.transparentShadows)
    defines.push_back("MG_TRANSPARENT_SHADOWS=1");
  // Cycles' Filter Glossy (path_shading.glsl filterGlossy), only for renders that ask for it,
  // so that the others' path state and kernels stay as they were. The constant is 1 / F, as
  // Cycles keeps it (scene/integrator.cpp), spelled by its bits so that it is exact.
  if (filterGlossyOn(b))
    defines.push_back("MG_FILTER_GLOSSY_INVERSE=uintBitsToFloat(" +
                      std::to_string(std::bit_cast<std::uint32_t>(1.0f / b.inputs.filterGlossy)) +
                      "u)");
  // Paths through opacities below 1 (stochastic_opacity.glsl), likewise only where a graph may
  // write one: the other scenes' traces stay as they were.
  if (!b.floor && b.inputs.materials->linked.stochasticOpacity)
    defines.push_back("MG_STOCHASTIC_OPACITY=1");
  return defines;
}

std::unique_ptr<FrameTracer> buildWavefront(const ShaderBuild& b, ShaderCompiler& compiler,
                                            const MaterialCache& cache,
                                            const std::vector<std::string>& defines,
                                            ShaderCacheStats& callableStats, RenderStats& stats) {
  WavefrontSetup setup;
  setup.materials = b.floor ? nullptr : &b.inputs.materials->linked;
  setup.cacheLookups = b.plan.cache.mode != CacheMode::None;
  setup.tileQueueCapacity = b.plan.cache.mode == CacheMode::Tile ? b.plan.cache.tileQueue : 0;
  setup.tileImage = cache.tileImageView() != VK_NULL_HANDLE;
  setup.emitterGraphs = b.inputs.materials->neeEvaluatesEmission && !b.floor;
  setup.lightPointGraphs = b.inputs.materials->neeEvaluatedGraphs;
  // The AO integrator ignores --shared-primary, as its megakernel does.
  setup.ambientOcclusionIntegrator = b.options.integrator == Integrator::AmbientOcclusion;
  setup.sharedPrimaryHits = b.settings.sharedPrimaryRay && !setup.ambientOcclusionIntegrator;
  setup.cutKeys = b.cutKeys;
  // A filtered read blends several entries in the material pass, which then runs the rest.
  setup.cutValuesToShade = b.cutKeys && b.plan.cache.filter == CacheFilter::Nearest;
  setup.pathSlots = b.options.wavefrontPaths;
  setup.compileThreads = b.options.shaderCompileThreads;
  setup.materialInstances = b.options.materialInstances;
  setup.ownPassesFromSecondFrame = b.options.ownMaterialPassesFromSecondFrame.value_or(
      b.context.info().type != VK_PHYSICAL_DEVICE_TYPE_CPU);
  setup.minRayPdf = filterGlossyOn(b);
  // LiPaC's hit feedback: one set of passes for every frame (a push constant says whether a
  // frame counts), where the megakernel keeps a second, quiet pipeline: only the trace pass
  // counts, and it is small.
  std::vector<std::string> passDefines = defines;
  if (b.inputs.hitFeedback)
    passDefines.push_back("MG_HIT_FEEDBACK=1");
  auto tracer = std::make_unique<WavefrontPathTracer>(
      b.context, compiler, b.inputs.scene->textures->count(), passDefines, b.settings.width,
      b.settings.height, setup);
  stats.wavefrontPathSlots = tracer->pathSlots();
  stats.wavefrontChunks = tracer->chunks();
  for (const WavefrontPathTracer::MaterialPassSize& size : tracer->materialPassSizes()) {
    ++stats.wavefrontMaterialPasses;
    stats.wavefrontMaterialInlinedInstructions += size.pass.inlinedInstructions;
    stats.wavefrontMaterialGraphInstructions += size.graph.inlinedInstructions;
    stats.wavefrontMaterialGraphCopiesMax =
        std::max(stats.wavefrontMaterialGraphCopiesMax, size.graph.copies);
  }
  // The wavefront has no callables: its material pipelines' compiles count in their place.
  callableStats = tracer->materialShaderStats();
  return tracer;
}

// LiPaC's hit counters and the counting-box probe, only where LiPaC runs; with
// --feedback-every K > 1 the frames that do not count trace with a second pipeline built
// without them, and a counting frame's paths that do not count (feedbackPaths N < P) do too.
// The debug view of cache misses writes each frame in one dispatch: a later one would
// overwrite it.
std::unique_ptr<FrameTracer> buildMegakernel(const ShaderBuild& b, ShaderCompiler& compiler,
                                             const MaterialCache& cache,
                                             const std::vector<std::string>& defines,
                                             const MaterialCallables* callables,
                                             RenderStats& stats) {
  const bool hitFeedback = b.inputs.hitFeedback;
  MegakernelSetup setup;
  setup.splitCounting = hitFeedback && b.plan.feedbackPathWeight > 1 && !b.options.debugCacheMisses;
  setup.pathsPerDispatch = b.options.debugCacheMisses ? 0u : b.options.pathsPerDispatch;
  setup.width = b.settings.width;
  setup.height = b.settings.height;
  setup.tileFillRows = cache.tileFillRows();
  setup.pipeline.callables = callables;
  // lavapipe (Mesa 25.0) gained nothing from a deferred operation (the classroom's pipeline
  // took as long, on one core) and crashes under the validation layer when handed one: keep
  // deferred pipeline creation to GPU drivers, where it can spread the compile.
  const std::uint32_t threads = b.options.shaderCompileThreads
                                    ? b.options.shaderCompileThreads
                                    : std::max(1u, std::thread::hardware_concurrency());
  setup.pipeline.pipelineThreads =
      b.context.info().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1 : threads;
  setup.pipeline.compileThreads = b.options.shaderCompileThreads;
  setup.pipeline.defines = defines;
  if (hitFeedback)
    setup.pipeline.defines.push_back("MG_HIT_FEEDBACK=1");
  setup.pipeline.tileImage = cache.tileImageView() != VK_NULL_HANDLE;
  setup.pipeline.tileFillPass = cache.tileFillRows() > 0;
  if (hitFeedback && (b.options.culling.feedbackEvery > 1 || setup.splitCounting))
    setup.quietDefines = defines;
  auto tracer = std::make_unique<MegakernelTracer>(b.context, compiler,
                                                   b.inputs.scene->textures->count(), setup);
  stats.rayTracingStack = tracer->stack();
  return tracer;
}

}  // namespace

RenderPipelines buildPipelines(const VulkanContext& context, const RendererOptions& options,
                               const RenderSettings& settings, const RenderPlan& plan,
                               const PipelineInputs& inputs, RenderStats& stats) {
  ShaderBuild b{context, options, settings, plan, inputs};
  // The AO integrator evaluates no graph: it compiles like the floor (the prelude only).
  b.floor = options.floorMaterials || options.integrator == Integrator::AmbientOcclusion;
  b.omitObjectInputs = b.floor || !inputs.materials->linked.objectInputs;
  b.omitPathInputs = b.floor || !inputs.materials->linked.pathInputs;
  b.omitTracedInputs = b.floor || !inputs.materials->linked.tracedInputs;
  b.omitBsdfLobes = b.floor || !inputs.materials->linked.bsdfLobes;
  const LinkedMaterials& materials = inputs.materials->linked;
  // Shaders: the embedded sources plus the generated materials.glsl; with callables, also
  // one callable shader per distinct material. The wavefront evaluates graphs in material
  // passes of its own, on either backend.
  std::map<std::string, std::string> files = embeddedShaderFiles();
  const bool callables = plan.dispatch == MaterialDispatch::Callable && !b.floor && !plan.wavefront;
  ShaderCacheStats callableStats;
  std::optional<MaterialCallables> materialCallables;
  if (callables)
    materialCallables = compileCallables(b, files, callableStats);
  b.cutKeys = keysCuts(plan, callables, b.floor, materials);
  files["materials.glsl"] =
      callables || b.floor || plan.wavefront ? materials.preludeSource : materials.source;
  files["material_rests.glsl"] = plan.wavefront && !b.floor ? materials.shadeRestSource : "";
  files["shadow_materials.glsl"] = plan.wavefront && !b.floor ? materials.shadowSource : "";
  ShaderCompiler compiler(std::move(files), inputs.shaderCacheDirectory);
  const auto pipelineStart = std::chrono::steady_clock::now();
  static_assert(static_cast<std::uint32_t>(CacheEviction::Lru) == gpu::kCacheEvictionLru &&
                static_cast<std::uint32_t>(CacheEviction::Lrw) == gpu::kCacheEvictionLrw &&
                static_cast<std::uint32_t>(CacheEviction::Random) == gpu::kCacheEvictionRandom);
  // The cache (thesis §5.3.1, §5.4.1): entries of a key hash, metadata and the largest
  // cacheable material's written outputs (per texel of a tile with the tile cache), or the
  // widest cut where the texel cache keys cuts, as fp32 or packed fp16.
  RenderPipelines pipelines;
  const std::uint32_t valueCount =
      b.cutKeys ? std::max(materials.cacheValueCount, materials.cutValueCount)
                : materials.cacheValueCount;
  pipelines.cache = std::make_unique<MaterialCache>(context, plan.cache, valueCount);
  pipelines.cache->describe(stats);
  const std::vector<std::string> defines = pathTracerDefines(b, *pipelines.cache);
  pipelines.tracer =
      plan.wavefront ? buildWavefront(b, compiler, *pipelines.cache, defines, callableStats, stats)
                     : buildMegakernel(b, compiler, *pipelines.cache, defines,
                                       materialCallables ? &*materialCallables : nullptr, stats);
  stats.pipelineCreateMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pipelineStart)
          .count() -
      compiler.stats().compileMilliseconds -
      (plan.wavefront ? callableStats.compileMilliseconds : 0.0);
  stats.shaderCompileMilliseconds =
      compiler.stats().compileMilliseconds + callableStats.compileMilliseconds;
  stats.shaderCacheHits = compiler.stats().hits + callableStats.hits;
  stats.shadersCompiled = compiler.stats().compiled + callableStats.compiled;
  return pipelines;
}

}  // namespace memograph::runtime
