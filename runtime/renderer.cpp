#include "runtime/renderer.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/accel/acceleration_structures.h"
#include "runtime/accel/culling_view.h"
#include "runtime/accel/dynamic_acceleration.h"
#include "runtime/materials/material_callables.h"
#include "runtime/materials/material_linker.h"
#include "runtime/memo/material_cache.h"
#include "runtime/scene/gpu_textures.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/megakernel/path_dispatches.h"
#include "runtime/trace/megakernel/trace_pipelines.h"
#include "runtime/trace/trace_descriptors.h"
#include "runtime/trace/wavefront/wavefront_path_tracer.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

constexpr std::uint32_t kMaxImageSide = 16384;

void validateSettings(const RenderSettings& s) {
  if (s.width == 0 || s.height == 0 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    throw std::invalid_argument("image size " + std::to_string(s.width) + "x" +
                                std::to_string(s.height) + " is out of range (1.." +
                                std::to_string(kMaxImageSide) + " per side)");
  if (s.pathsPerPixel == 0)
    throw std::invalid_argument("paths per pixel must be at least 1");
  if (s.raysPerPath == 0)
    throw std::invalid_argument("rays per path must be at least 1");
  if (s.frames == 0)
    throw std::invalid_argument("frames must be at least 1");
}

// What one counted path's ray weighs when `counted` of a pixel's `paths` paths count in a
// LiPaC counting frame (CullingOptions::feedbackPaths): paths / counted, so `counted` must
// divide `paths`; 1 where every path counts (0, or at least `paths`).
std::uint32_t feedbackPathWeight(std::uint32_t counted, std::uint32_t paths) {
  if (counted == 0 || counted >= paths)
    return 1;
  if (paths % counted != 0)
    throw std::invalid_argument("--feedback-paths " + std::to_string(counted) +
                                " must divide the paths per pixel (" + std::to_string(paths) +
                                "): each counted path stands for paths / N; 0 counts every path");
  return paths / counted;
}

bool sameCamera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.target == b.target && a.up == b.up &&
         a.verticalFovDegrees == b.verticalFovDegrees;
}

// Camera basis and the primary ray cone's spread angle (thesis §2.2: one pixel's angle).
void setCamera(gpu::FrameConstants& frame, const Camera& camera, std::uint32_t width,
               std::uint32_t height) {
  glm::vec3 forward = camera.target - camera.position;
  if (glm::dot(forward, forward) < 1e-20f)
    throw std::invalid_argument("the camera's position and target coincide");
  if (!(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f))
    throw std::invalid_argument("the camera's vertical field of view must be in (0, 180) degrees");
  forward = glm::normalize(forward);
  glm::vec3 right = glm::cross(forward, camera.up);
  if (glm::dot(right, right) < 1e-12f)
    throw std::invalid_argument("the camera's up vector is parallel to its view direction");
  right = glm::normalize(right);
  glm::vec3 up = glm::cross(right, forward);
  float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  float aspect = float(width) / float(height);
  float pixelSpread = std::atan(2.0f * tanHalf / float(height));
  frame.cameraPosition = glm::vec4(camera.position, pixelSpread);
  frame.cameraRight = glm::vec4(right * tanHalf * aspect, 0.0f);
  frame.cameraUp = glm::vec4(up * tanHalf, 0.0f);
  frame.cameraForward = glm::vec4(forward, frame.cameraForward.w);
}

MaterialDispatch resolveMaterialDispatch(MaterialDispatch requested, Backend backend) {
  if (requested == MaterialDispatch::Auto)
    return backend == Backend::RayTracingPipeline ? MaterialDispatch::Callable
                                                  : MaterialDispatch::Switch;
  if (requested == MaterialDispatch::Callable && backend != Backend::RayTracingPipeline)
    throw std::invalid_argument(
        "--material-dispatch callable needs the ray-tracing pipeline backend (--backend "
        "pipeline); compute shaders (the query backend) have no callable shaders");
  return requested;
}

}  // namespace

TextureImage loadTextureCore(const std::string& path) {
  std::filesystem::path p(path);
  if (!std::filesystem::exists(p))
    throw std::runtime_error("texture not found: " + path);
  auto extension = p.extension().string();
  if (extension != ".pfm" && extension != ".PFM") {
    throw std::runtime_error("texture '" + path +
                             "': the core renderer reads only PFM; render through the "
                             "memograph CLI (OpenImageIO) or convert it to .pfm");
  }
  return TextureImage{{readPfm(p)}};
}

const char* shadingName(Shading shading) {
  switch (shading) {
    case Shading::Auto:
      return "auto";
    case Shading::Wavefront:
      return "wavefront";
    case Shading::Megakernel:
      break;
  }
  return "megakernel";
}

Shading parseShading(const std::string& text) {
  if (text == "auto")
    return Shading::Auto;
  if (text == "megakernel")
    return Shading::Megakernel;
  if (text == "wavefront")
    return Shading::Wavefront;
  throw std::invalid_argument("--shading takes auto, megakernel or wavefront, not '" + text + "'");
}

// What the wavefront prototype cannot do that the options ask, in words that follow "it"
// ("--shading wavefront is a prototype: it ...", or auto's reason); empty when it can.
static std::string wavefrontOptionGap(const RendererOptions& options) {
  const CacheOptions& cache = options.cache;
  if (cache.mode != CacheMode::None && options.floorMaterials)
    return "it fills the cache in its material passes, and the free-material floor has none "
           "(time the floor's lookups with --shading megakernel)";
  if (options.culling.mode != CullingMode::None)
    return "it has no culling (--culling none)";
  if (options.debugCacheMisses)
    return "it has no --debug-misses view";
  if (options.debugCullingSize > 0)
    return "it has no --debug-culling view";
  if (cache.mode == CacheMode::Tile &&
      (cache.tileFill == TileFill::Subgroup || cache.groupByMaterial || cache.testRepacks))
    return "it computes missing tiles from the deferred fill's queue; --tile-fill subgroup and "
           "its grouping and test hook are the megakernel's";
  return {};
}

// The same for the scene and the device, after the options' gaps.
static std::string wavefrontGap(const RendererOptions& options, const Scene& scene,
                                const ShadingDevice& device, bool neeEvaluatesEmission) {
  std::string gap = wavefrontOptionGap(options);
  if (!gap.empty())
    return gap;
  if (!device.wavefrontTraces)
    return "on the pipeline backend it launches its traces with vkCmdTraceRaysIndirectKHR, "
           "which the device lacks (use --backend query)";
  if (!scene.animatedMeshes.empty() && !scene.animatedMotions.empty())
    return "it renders static scenes only, and this one has animated meshes";
  if (neeEvaluatesEmission && !options.floorMaterials)
    return "it evaluates no emitter's graph for a light sample, and this scene's emission is "
           "not a known constant";
  return {};
}

void validateWavefrontOptions(const RendererOptions& options) {
  if (options.shading == Shading::Megakernel && options.wavefrontPaths > 0)
    throw std::invalid_argument(
        "--wavefront-paths sets the wavefront's paths in flight; it needs --shading wavefront");
  // Auto: render() decides once it knows the device and the scene.
  if (options.shading != Shading::Wavefront)
    return;
  const std::string gap = wavefrontOptionGap(options);
  if (!gap.empty())
    throw std::invalid_argument("--shading wavefront is a prototype: " + gap);
}

// Auto: the wavefront on a GPU. On an NVIDIA H200 (1920x1080, P = 6, L = 4, the pipeline
// backend) it was faster than the megakernel in all eight configurations measured
// (docs/architecture.md, "Material-coherent shading"): the classroom 47.6 against 73.1 ms on
// the floor, 96.7 against 2762 ms without a cache, 93.5 against 148.4 ms with the texel cache,
// 95.0 against 181.6 ms with the tile cache; the landscape 23.3 against 30.6, 33.6 against
// 203.7, 32.6 against 77.5 and 31.8 against 96.5 ms. Sorting hits by material keeps a GPU's
// lanes on one graph, where the megakernel's lanes diverge over many. On lavapipe (a CPU) the
// two could not be ranked (the megakernel ahead on the floor, 34.9 against 38.5 ms), so it
// keeps the megakernel. Anything the wavefront prototype cannot do (wavefrontGap) picks the
// megakernel too; an explicit --shading wavefront is refused for it instead.
ShadingChoice resolveShading(const RendererOptions& options, const Scene& scene,
                             const ShadingDevice& device, bool neeEvaluatesEmission) {
  if (options.shading != Shading::Auto)
    return {options.shading, ""};
  if (device.type == VK_PHYSICAL_DEVICE_TYPE_CPU)
    return {Shading::Megakernel,
            "the device is a CPU, where the wavefront was not measured faster"};
  const std::string gap = wavefrontGap(options, scene, device, neeEvaluatesEmission);
  if (!gap.empty())
    return {Shading::Megakernel, "the wavefront prototype cannot do what is asked: " + gap};
  return {Shading::Wavefront, ""};
}

std::size_t countDistinctMaterialGraphs(const Scene& scene) {
  std::set<std::pair<std::string, std::string>> graphs;
  for (const auto& material : scene.materials) {
    graphs.emplace(material.graphPath, material.graphText);
  }
  return graphs.size();
}

// Only the pipeline backend has a closest-hit shader to bump LiPaC's counters in
// (--hit-counters closest-hit): --backend auto picks it then.
static ContextOptions contextOptionsFor(const RendererOptions& options) {
  ContextOptions context = options.context;
  if (options.culling.mode == CullingMode::Lipac && options.culling.countersInClosestHit)
    context.autoPrefersPipeline = true;
  return context;
}

Renderer::Renderer(RendererOptions options)
    : options_(std::move(options)),
      context_(std::make_unique<VulkanContext>(contextOptionsFor(options_))) {}

Renderer::~Renderer() = default;

RenderResult Renderer::render(const Scene& scene, const RenderSettings& settings) {
  validateSettings(settings);
  validateScene(scene);
  validateCullingOptions(options_.culling);
  const std::uint32_t pathWeight =
      options_.culling.mode == CullingMode::Lipac
          ? feedbackPathWeight(options_.culling.feedbackPaths, settings.pathsPerPixel)
          : 1;
  validateWavefrontOptions(options_);
  if (options_.debugCullingSize > 0 && options_.culling.mode == CullingMode::None)
    throw std::invalid_argument(
        "--debug-culling shows which instances culling keeps; it needs --culling frustum or "
        "--culling lipac");
  const VulkanContext& context = *context_;
  if (options_.culling.mode == CullingMode::Lipac && options_.culling.countersInClosestHit &&
      context.backend() == Backend::RayQuery)
    throw std::invalid_argument(
        "--hit-counters closest-hit needs the ray-tracing pipeline backend (--backend "
        "pipeline): a ray query has no closest-hit shader");
  if (options_.culling.blasBuildMilliseconds > 0.0 && !context.info().timestamps)
    throw std::invalid_argument(
        "--blas-build-ms times the BLAS builds with GPU timestamps, which this device does not "
        "have; --blas-build-budget limits the triangles built instead");

  // Materials: graphs → GLSL, and the textures they name. Linked first: whether NEE must
  // evaluate an emitter's graph decides what Shading::Auto can run.
  MaterialLinkOptions linkOptions;
  linkOptions.nodeLibraryDirectory = options_.nodeLibraryDirectory;
  LinkedMaterials materials = linkMaterials(scene.materials, linkOptions);
  const std::size_t distinctMaterials = materials.distinct.size();
  const std::vector<MaterialRef::EmissionKind> emissionKinds =
      emissionKindsVerified(scene, materials);
  ShadingDevice shadingDevice;
  shadingDevice.type = context.info().type;
  shadingDevice.wavefrontTraces =
      context.backend() == Backend::RayQuery || context.info().traceRaysIndirect;
  // Some emitter's emission NEE must take from its graph: the megakernel's second material
  // call site (MG_NEE_EVALUATES_EMISSION), which the wavefront does not have.
  const bool neeEvaluatesEmission = sceneNeeEvaluatesEmission(scene, emissionKinds);
  const ShadingChoice shading =
      resolveShading(options_, scene, shadingDevice, neeEvaluatesEmission);
  const bool wavefront = shading.shading == Shading::Wavefront;
  if (options_.wavefrontPaths > 0 && !wavefront)
    throw std::invalid_argument(
        "--wavefront-paths sets the wavefront's paths in flight; it needs the wavefront, which "
        "--shading auto did not choose: " +
        shading.whyMegakernel + " (--shading wavefront asks for it)");
  if (options_.shading == Shading::Wavefront) {
    const std::string gap = wavefrontGap(options_, scene, shadingDevice, neeEvaluatesEmission);
    if (!gap.empty())
      throw std::invalid_argument("--shading wavefront is a prototype: " + gap +
                                  " (--shading megakernel or auto)");
  }
  VkDevice device = context.device();
  RenderResult result;
  RenderStats& stats = result.stats;
  stats.device = context.info().name;
  stats.backend = backendName(context.backend());
  stats.width = settings.width;
  stats.height = settings.height;
  stats.pathsPerPixel = settings.pathsPerPixel;
  stats.raysPerPath = settings.raysPerPath;

  // The image is one storage buffer of 4 floats a pixel: refused before anything compiles
  // when the device cannot bind it whole.
  const std::uint64_t accumulationBytes =
      std::uint64_t(settings.width) * settings.height * sizeof(glm::vec4);
  checkBufferSize(context, accumulationBytes,
                  "a " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                      " image (16 bytes a pixel)",
                  true);

  MaterialDispatch dispatch = resolveMaterialDispatch(options_.materialDispatch, context.backend());
  // Unset clock options resolved for this device (cache_options.h).
  // The wavefront computes missing tiles in its material passes, from the deferred fill's
  // queue: there is no subgroup of lookups to share a tile's texels out (an explicit subgroup
  // fill is a wavefrontGap).
  CacheOptions requested = options_.cache;
  if (wavefront && requested.mode == CacheMode::Tile)
    requested.tileFill = TileFill::Deferred;
  const CacheOptions cache = resolveCacheOptions(requested, context.info().bufferInt64Atomics,
                                                 std::uint64_t(settings.width) * settings.height *
                                                     settings.pathsPerPixel * settings.raysPerPath);
  const bool cacheOn = cache.mode != CacheMode::None;
  if (cacheOn) {
    // Before minutes of material compiles.
    validateCacheOptions(cache);
    validateCacheOnDevice(context, cache);
    if (cache.clock == CacheClock::Counter && !context.info().bufferInt64Atomics)
      throw std::runtime_error(
          "--clock counter needs 64-bit atomics on storage buffers "
          "(shaderInt64 and shaderBufferInt64Atomics), which " +
          context.info().name + " lacks; use --clock frame");
  }
  if (options_.debugCacheMisses && !cacheOn)
    throw std::invalid_argument(
        "--debug-misses shows cache misses; it needs --cache texel or --cache tile");

  // The wavefront compiles each graph into a pipeline of its own: no switch to outgrow.
  if (dispatch == MaterialDispatch::Switch && !options_.floorMaterials && !wavefront &&
      context.info().type == VK_PHYSICAL_DEVICE_TYPE_CPU && options_.cpuSwitchMaterialLimit > 0 &&
      distinctMaterials > options_.cpuSwitchMaterialLimit) {
    // Fail in a second rather than after minutes and gigabytes of LLVM.
    throw std::runtime_error(
        "this scene has " + std::to_string(distinctMaterials) +
        " distinct materials; compiling them into one path-tracer shader (the switch "
        "dispatch) would take about " +
        std::to_string((distinctMaterials * 110 + 500) / 1000) + " GB and minutes on " +
        context.info().name + " (about 110 MB per material). Render with " +
        (context.backend() == Backend::RayQuery
             ? std::string("--backend pipeline, which compiles one small callable shader per "
                           "material, or --shading wavefront, one small pipeline per material")
             : std::string("--material-dispatch callable (the pipeline backend's default)")) +
        " (library callers: or raise RendererOptions::cpuSwitchMaterialLimit, now " +
        std::to_string(options_.cpuSwitchMaterialLimit) + ")");
  }
  stats.materialCount = static_cast<std::uint32_t>(scene.materials.size());
  stats.materialCompileMilliseconds = materials.compileMilliseconds;
  std::vector<TextureImage> textureImages;
  for (const auto& path : materials.texturePaths)
    textureImages.push_back(options_.textureLoader(path));

  // Where compiled shaders are kept (none without the cache).
  std::filesystem::path cacheDirectory;
  if (options_.shaderCache) {
    cacheDirectory = options_.shaderCacheDirectory.empty() ? defaultShaderCacheDirectory()
                                                           : options_.shaderCacheDirectory;
  }

  // Scene data, acceleration structures, textures.
  SceneBuffers buffers = uploadScene(context, scene, emissionKinds);
  const CullingOptions& cullingOptions = options_.culling;
  stats.culling = std::string(cullingModeName(cullingOptions.mode));
  // Without culling, every BLAS and the TLAS are built once here; culled renders rebuild the
  // TLAS every frame from the instances the frame keeps.
  std::optional<SceneAccelerationStructures> staticAccel;
  std::optional<DynamicAccelerationStructures> dynamicAccel;
  GpuBuffer noHitFeedback;
  // Animated meshes move every frame: their BLASes are updated and the TLAS rebuilt, as in
  // a culled render.
  const bool animated = !scene.animatedMeshes.empty() && !scene.animatedMotions.empty();
  if (cullingOptions.mode == CullingMode::None && !animated) {
    staticAccel.emplace(context, buffers.vertices, sizeof(gpu::Vertex), buffers.indices,
                        buffers.geometry, buffers.placements);
    stats.accelerationStructures = staticAccel->stats();
    noHitFeedback = GpuBuffer(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  } else {
    dynamicAccel.emplace(context, scene, buffers, cullingOptions, cacheDirectory, pathWeight);
    stats.accelerationStructures.blasCount = static_cast<std::uint32_t>(buffers.geometry.size());
    stats.accelerationStructures.instanceCount = static_cast<std::uint32_t>(scene.instances.size());
  }
  const bool hitFeedback = dynamicAccel && dynamicAccel->hitFeedbackOn();
  GpuTextures textures(context, textureImages);
  stats.textureBytes = textures.bytes();

  // Shaders: the embedded sources plus the generated materials.glsl; with callables, also
  // one callable shader per distinct material.
  std::map<std::string, std::string> files = embeddedShaderFiles();
  // The floor run compiles no graph: the prelude (types, defaults) and no callables.
  const bool floor = options_.floorMaterials;
  // The wavefront evaluates graphs in material passes of its own, on either backend.
  bool callables = dispatch == MaterialDispatch::Callable && !floor && !wavefront;
  stats.materialDispatch = floor ? "floor" : wavefront ? "batched" : materialDispatchName(dispatch);
  ShaderCacheStats callableStats;
  std::optional<MaterialCallables> materialCallables;
  // MaterialInputs without the object-space members when no graph reads them: the callable
  // payload and the raygen's stack shrink (on the H200 the classroom's texel row: 144.7 ms
  // and a 896 B stack with them, 128.5 ms and 576 B without).
  const bool omitObjectInputs = floor || !materials.objectInputs;
  if (callables) {
    MaterialCallableCompileOptions callableOptions;
    if (omitObjectInputs)
      callableOptions.defines.push_back("MG_OMIT_OBJECT_INPUTS=1");
    callableOptions.files = files;
    callableOptions.cacheDirectory = cacheDirectory;
    callableOptions.textureCount = textures.count();
    callableOptions.threads = options_.shaderCompileThreads;
    materialCallables = compileMaterialCallables(materials, callableOptions, callableStats);
  }
  files["materials.glsl"] =
      callables || floor || wavefront ? materials.preludeSource : materials.source;
  ShaderCompiler compiler(std::move(files), cacheDirectory);
  auto pipelineStart = std::chrono::steady_clock::now();
  std::uint32_t threads = options_.shaderCompileThreads
                              ? options_.shaderCompileThreads
                              : std::max(1u, std::thread::hardware_concurrency());
  // lavapipe (Mesa 25.0) gained nothing from a deferred operation (the classroom's pipeline
  // took as long, on one core) and crashes under the validation layer when handed one: keep
  // deferred pipeline creation to GPU drivers, where it can spread the compile.
  std::uint32_t pipelineThreads = context.info().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1 : threads;
  static_assert(static_cast<std::uint32_t>(CacheEviction::Lru) == gpu::kCacheEvictionLru &&
                static_cast<std::uint32_t>(CacheEviction::Lrw) == gpu::kCacheEvictionLrw &&
                static_cast<std::uint32_t>(CacheEviction::Random) == gpu::kCacheEvictionRandom);
  // The cache (thesis §5.3.1, §5.4.1): entries of a key hash, metadata and the largest
  // cacheable material's written outputs (per texel of a tile with the tile cache), as fp32
  // or packed fp16.
  MaterialCache materialCache(context, cache, materials.cacheValueCount);
  materialCache.describe(stats);
  std::vector<std::string> shaderDefines = materialCache.defines();
  if (floor)
    shaderDefines.push_back("MG_MATERIAL_FLOOR=1");
  if (omitObjectInputs)
    shaderDefines.push_back("MG_OMIT_OBJECT_INPUTS=1");
  if (options_.debugCacheMisses)
    shaderDefines.push_back("MG_DEBUG_CACHE_MISSES=1");
  // Cycles' Principled weighting, only for scenes whose materials write it (brdf.glsl).
  if (materials.cyclesPrincipled && !floor)
    shaderDefines.push_back("MG_CYCLES_PRINCIPLED=1");
  // Emissive-triangle NEE and its MIS, only for scenes with emissive triangles; with free
  // materials too, so the floor traces the same rays. NEE evaluates emitters whose emission
  // is not a known constant: a second material call site, compiled only for scenes that
  // have such emitters (path_tracer.glsl).
  if (buffers.emissiveTriangles)
    shaderDefines.push_back("MG_EMISSIVE_NEE=1");
  if (neeEvaluatesEmission && !floor)
    shaderDefines.push_back("MG_NEE_EVALUATES_EMISSION=1");  // never the wavefront (wavefrontGap)
  // LiPaC's hit counters and the counting-box probe, only where LiPaC runs; with
  // --feedback-every K > 1 the frames that do not count trace with a second pipeline built
  // without them (the same bindings, so the same descriptor set), and with
  // --feedback-dispatch split a counting frame's paths that do not count do too. The debug
  // view of cache misses writes each frame in one dispatch: a later one would overwrite it.
  const bool splitCounting = hitFeedback && options_.culling.splitFeedbackDispatch &&
                             pathWeight > 1 && !options_.debugCacheMisses;
  const std::uint32_t pathsPerDispatch = options_.debugCacheMisses ? 0u : options_.pathsPerDispatch;
  const std::vector<std::string> quietDefines = shaderDefines;
  if (hitFeedback)
    shaderDefines.push_back("MG_HIT_FEEDBACK=1");
  // --hit-counters closest-hit: the feedback's pipeline bumps the counters in its closest-hit
  // shader (the pipeline backend; the constructor refuses it on the query backend).
  const bool closestHitCounts = hitFeedback && options_.culling.countersInClosestHit;
  // One architecture or the other: the megakernel's pipeline, or the wavefront's passes.
  std::optional<TracePipeline> pipeline;
  std::optional<TracePipeline> quietPipeline;
  std::optional<WavefrontPathTracer> wavefrontTracer;
  stats.shading = shadingName(shading.shading);
  if (wavefront) {
    WavefrontSetup setup;
    setup.materials = floor ? nullptr : &materials;
    setup.cacheLookups = cacheOn;
    setup.tileQueueCapacity = cache.mode == CacheMode::Tile ? cache.tileQueue : 0;
    setup.tileImage = materialCache.tileImageView() != VK_NULL_HANDLE;
    setup.pathSlots = options_.wavefrontPaths;
    setup.compileThreads = options_.shaderCompileThreads;
    wavefrontTracer.emplace(context, compiler, textures.count(), shaderDefines, settings.width,
                            settings.height, setup);
    stats.wavefrontPathSlots = wavefrontTracer->pathSlots();
    stats.wavefrontChunks = wavefrontTracer->chunks();
    // The wavefront has no callables: its material pipelines' compiles count in their place.
    callableStats = wavefrontTracer->materialShaderStats();
  } else {
    TracePipelineSetup setup;
    setup.callables = materialCallables ? &*materialCallables : nullptr;
    setup.pipelineThreads = pipelineThreads;
    setup.defines = shaderDefines;
    setup.tileImage = materialCache.tileImageView() != VK_NULL_HANDLE;
    setup.tileFillPass = materialCache.tileFillRows() > 0;
    setup.closestHitCounts = closestHitCounts;
    setup.closestHitBindings = closestHitCounts;
    pipeline.emplace(context, compiler, textures.count(), setup);
    stats.rayTracingStack = pipeline->stack();
    if (hitFeedback && (options_.culling.feedbackEvery > 1 || splitCounting)) {
      setup.defines = quietDefines;
      setup.closestHitCounts = false;
      quietPipeline.emplace(context, compiler, textures.count(), setup);
    }
  }
  stats.pipelineCreateMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pipelineStart)
          .count() -
      compiler.stats().compileMilliseconds - (wavefront ? callableStats.compileMilliseconds : 0.0);
  stats.shaderCompileMilliseconds =
      compiler.stats().compileMilliseconds + callableStats.compileMilliseconds;
  stats.shaderCacheHits = compiler.stats().hits + callableStats.hits;
  stats.shadersCompiled = compiler.stats().compiled + callableStats.compiled;

  // Per-render buffers.
  std::size_t pixelCount = std::size_t(settings.width) * settings.height;
  GpuBuffer frameBuffer =
      hostBuffer(context, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  GpuBuffer accumulation(context, accumulationBytes,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  GpuBuffer rayCounter(context, sizeof(gpu::Counters),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  GpuBuffer rayReadback =
      hostBuffer(context, sizeof(gpu::Counters), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  TraceResources resources{staticAccel ? staticAccel->tlas() : dynamicAccel->tlas(),
                           &frameBuffer,
                           &accumulation,
                           &rayCounter,
                           &materialCache,
                           &buffers,
                           &textures,
                           dynamicAccel ? &dynamicAccel->hitFeedback() : &noHitFeedback,
                           dynamicAccel ? dynamicAccel->countingBoxes() : VK_NULL_HANDLE};
  if (wavefrontTracer) {
    resources.pathState = &wavefrontTracer->pathState();
    resources.pathQueues = &wavefrontTracer->pathQueues();
    resources.wavefrontControl = &wavefrontTracer->control();
  }
  TraceDescriptorSet descriptors(
      context,
      wavefrontTracer ? wavefrontTracer->descriptorSetLayout() : pipeline->descriptorSetLayout(),
      resources);
  VkDescriptorSet set = descriptors.get();

  // Timestamps around each frame's trace, then a dynamic set's animated BLASes and TLAS, then
  // the wavefront's, one after each pass.
  bool timestamps = context.info().timestamps;
  VulkanHandle<VkQueryPool> timestampPool;
  constexpr std::uint32_t kFirstWavefrontTimestamp = 5;
  const std::uint32_t wavefrontTimestamps =
      wavefrontTracer
          ? wavefrontTracer->timestampCount(settings.pathsPerPixel, settings.raysPerPath)
          : 0;
  const std::uint32_t timestampCount = kFirstWavefrontTimestamp + wavefrontTimestamps;
  if (timestamps) {
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = timestampCount;
    VkQueryPool queryPool = VK_NULL_HANDLE;
    checkVk(vkCreateQueryPool(device, &queryInfo, nullptr, &queryPool), "vkCreateQueryPool");
    timestampPool = VulkanHandle<VkQueryPool>(
        queryPool, [device](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });
  }

  gpu::FrameConstants frame{};
  frame.environment = scene.environment.imageRgb.empty()
                          ? glm::vec4(scene.environment.constantRadiance, 0.0f)
                          : glm::vec4(1.0f, 1.0f, 1.0f, 0.0f);
  frame.image = glm::uvec4(settings.width, settings.height, 0, settings.seed);
  std::uint32_t flags = (settings.sharedPrimaryRay ? gpu::kFlagSharedPrimaryRay : 0u) |
                        (buffers.environmentWidth ? gpu::kFlagEnvironmentImage : 0u);
  frame.path = glm::uvec4(settings.pathsPerPixel, settings.raysPerPath, flags, buffers.lightCount);
  frame.environmentSize = glm::uvec4(buffers.environmentWidth, buffers.environmentHeight, 0, 0);
  // LiPaC's sampling: x the blocks' stride, z the paths that count (0: every one).
  frame.culling = glm::uvec4(options_.culling.feedbackStride, 0,
                             pathWeight > 1 ? options_.culling.feedbackPaths : 0u, 0);
  std::uint32_t mipBiasBits = 0;
  std::memcpy(&mipBiasBits, &cache.mipBias, sizeof mipBiasBits);
  frame.cache =
      glm::uvec4(materialCache.entryCount(), 0u, mipBiasBits, materialCache.tilesPerRow());

  // One frame's commands: clears, the TLAS build, the trace (and tile fill), the read-backs.
  // `f` == 0 clears the cache and the counters that persist. `dispatches`: the trace's
  // dispatches in order (planPathDispatches), each with the pipeline with LiPaC's feedback
  // or, where there is one, without it.
  const auto submitFrame = [&](std::uint32_t f, const std::vector<PathDispatch>& dispatches) {
    const TracePipeline* tracer = pipeline ? &*pipeline : nullptr;
    context.submitAndWait([&](VkCommandBuffer commands) {
      // The cache is cleared once, before the first frame: every key kCacheKeyEmpty (0),
      // every clock 0, and with it the counters that persist (occupancy, counter clock);
      // the per-frame counters and the tile log every frame. The barrier below orders them
      // before the trace.
      vkCmdFillBuffer(commands, rayCounter.buffer(), 0,
                      f == 0 ? VK_WHOLE_SIZE : gpu::kCountersPerFrameUints * sizeof(std::uint32_t),
                      0);
      materialCache.recordClears(commands, f == 0);
      if (dynamicAccel)
        dynamicAccel->recordClears(commands);
      VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                           nullptr);
      if (timestamps)
        vkCmdResetQueryPool(commands, timestampPool.get(), 0, timestampCount);
      if (dynamicAccel)
        dynamicAccel->recordTlasBuild(commands, timestamps ? timestampPool.get() : VK_NULL_HANDLE,
                                      2);
      if (timestamps)
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestampPool.get(), 0);
      if (wavefrontTracer)
        wavefrontTracer->record(commands, set, settings.pathsPerPixel, settings.raysPerPath,
                                timestamps ? timestampPool.get() : VK_NULL_HANDLE,
                                kFirstWavefrontTimestamp);
      else {
        for (const PathDispatch& d : dispatches) {
          // A later dispatch adds its share to what the earlier ones wrote (renderPixel).
          if (d.adds) {
            barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
            barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
            vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                                 VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                                 nullptr);
          }
          const TracePipeline& traced = quietPipeline && !d.feedback ? *quietPipeline : *tracer;
          traced.record(commands, set, settings.width, settings.height, d.push());
        }
      }
      if (materialCache.tileFillRows() > 0 && pipeline) {
        // The deferred tile fill computes the tiles the trace queued (its stores, queue and
        // locks ordered after the trace's); the frame's time includes it.
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                             VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                             nullptr);
        tracer->recordTileFill(commands, set, materialCache.tileFillRows());
      }
      if (timestamps)
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestampPool.get(), 1);
      barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
      barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
      VkBufferCopy copy{0, 0, sizeof(gpu::Counters)};
      vkCmdCopyBuffer(commands, rayCounter.buffer(), rayReadback.buffer(), 1, &copy);
      if (dynamicAccel)
        dynamicAccel->recordAfterTrace(commands);
    });
  };

  // The last submitted frame's timestamps first..first+count-1 (0, 1: the trace; 2-4: the
  // builds; from kFirstWavefrontTimestamp: the wavefront's passes).
  const double millisecondsPerTick = context.info().timestampPeriodNs * 1e-6;
  const auto readTimestamps = [&](std::uint32_t first, std::uint32_t count, std::uint64_t* ticks) {
    checkVk(vkGetQueryPoolResults(device, timestampPool.get(), first, count,
                                  count * sizeof(std::uint64_t), ticks, sizeof(std::uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults (timestamps)");
  };

  Camera previousCamera;
  std::uint32_t sampleIndex = 0;
  std::uint64_t previousRays = 0;
  for (std::uint32_t f = 0; f < settings.frames; ++f) {
    const Camera& camera =
        settings.cameraPath.empty()
            ? scene.camera
            : settings.cameraPath[std::min<std::size_t>(f, settings.cameraPath.size() - 1)];
    if (f > 0 && !sameCamera(camera, previousCamera))
      sampleIndex = 0;
    previousCamera = camera;
    frame.cameraForward.w = float(f) * settings.secondsPerFrame;
    setCamera(frame, camera, settings.width, settings.height);
    frame.image.z = f;
    frame.culling.y = f / options_.culling.feedbackEvery;  // the counting frame's index
    frame.environmentSize.z = sampleIndex;
    frame.cache.y = f + 1u;  // the frame clock of §5.3.3 (0: never used)
    frameBuffer.write(&frame, sizeof frame);
    FrameStats frameStats;
    frameStats.frame = f;
    FrameStats look;
    const float aspect = float(settings.width) / float(settings.height);
    // A look only where the frame starts the pixels' sums afresh (a new camera), so that the
    // probe's sample is replaced, not averaged in.
    if (sampleIndex == 0 && dynamicAccel &&
        dynamicAccel->prepareLook(camera, aspect, f, frame.cameraForward.w, look)) {
      // LiPaC's look (SceneCulling::look): one trace of this frame's camera, its image replaced
      // by the frame's, its builds, host and GPU time folded into the frame's figures, its
      // counters read by the frame's culling update. The probe traces one path a pixel and
      // counts every ray of it: it is one trace that decides what the frame holds, and with 1
      // in feedbackStride blocks counted an instance seen in a few pixels could go unseen (the
      // small city's first frame at 64x36 differed from the unculled one by 1.14 % of the
      // image's mean, against 0.78 % with every ray counted:
      // CulledRender.TheFirstLookHoldsWhatTheFirstCameraReaches). One path, not P: its image
      // is not kept, and on the H200 at P = 6 a frame with a look of P paths took 1.6-2.5x the
      // unculled frame's time (with one path 1.10x). For the same reason its paths trace no
      // shadow rays (frame.culling.w).
      const glm::uvec4 framePath = frame.path, frameCulling = frame.culling;
      frame.path.x = 1u;
      frame.culling = glm::uvec4(1u, frame.culling.y, 0u, gpu::kCullingLook);
      frameBuffer.write(&frame, sizeof frame);
      submitFrame(f, planPathDispatches(1, pathsPerDispatch, true, false, {0, 1}));
      frame.path = framePath;
      frame.culling = frameCulling;
      frameBuffer.write(&frame, sizeof frame);
      gpu::Counters counters{};
      rayReadback.read(&counters, sizeof counters);
      previousRays = look.lookRays = counters.rays;
      if (timestamps) {
        std::uint64_t ticks[5] = {0, 0, 0, 0, 0};
        readTimestamps(0, 5, ticks);
        look.lookMilliseconds = double(ticks[1] - ticks[0]) * millisecondsPerTick;
        look.blasBuildMilliseconds += double(ticks[3] - ticks[2]) * millisecondsPerTick;
        look.tlasBuildMilliseconds = double(ticks[4] - ticks[3]) * millisecondsPerTick;
      }
    }
    if (dynamicAccel) {
      dynamicAccel->prepareFrame(camera, aspect, f, frame.cameraForward.w, previousRays,
                                 frameStats);
    } else {
      const AccelerationStructureStats& a = staticAccel->stats();
      frameStats.activeInstances = frameStats.tlasRecords = a.instanceCount;
      frameStats.blasBytes = a.blasBytes;
      frameStats.tlasBytes = a.tlasBytes;
      frameStats.asScratchBytes = staticAccel->residentScratchBytes();
    }

    const bool counts = dynamicAccel && dynamicAccel->frameCounts();
    frameStats.feedbackFrame = counts ? 1u : 0u;
    const std::vector<PathDispatch> dispatches =
        planPathDispatches(settings.pathsPerPixel, pathsPerDispatch, counts, splitCounting,
                           countedPaths(settings.pathsPerPixel, frame.culling.z, frame.culling.y));
    frameStats.traceDispatches = wavefrontTracer ? 0u : std::uint32_t(dispatches.size());
    auto start = std::chrono::steady_clock::now();
    submitFrame(f, dispatches);
    frameStats.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gpu::Counters counters{};
    rayReadback.read(&counters, sizeof counters);
    frameStats.rays = counters.rays;
    previousRays = counters.rays;
    frameStats.cacheLookups = counters.cacheLookups;
    frameStats.cacheHits = counters.cacheHits;
    frameStats.cacheMisses = counters.cacheMisses;
    frameStats.cacheOccupancy = counters.cacheOccupancy;
    frameStats.cacheClockTicks = counters.cacheClock;
    frameStats.cacheTilesComputed = counters.cacheTilesComputed;
    frameStats.cacheDuplicateTiles = counters.cacheDuplicateTiles;
    frameStats.cacheTileFallbacks = counters.cacheTileFallbacks;
    frameStats.cacheTileRepacks = counters.cacheTileRepacks;
    frameStats.cacheLocksBesideALock = counters.cacheLocksBesideALock;
    frameStats.cacheLocksContended = counters.cacheLocksContended;
    frameStats.cacheTilesPublished = counters.cacheTilesPublished;
    if (wavefrontTracer)
      frameStats.wavefrontBinHits = wavefrontTracer->binHits();
    if (timestamps) {
      std::uint64_t ticks[5] = {0, 0, 0, 0, 0};
      readTimestamps(0, dynamicAccel ? 5 : 2, ticks);
      frameStats.gpuMilliseconds = double(ticks[1] - ticks[0]) * millisecondsPerTick;
      if (dynamicAccel) {
        frameStats.blasBuildMilliseconds += double(ticks[3] - ticks[2]) * millisecondsPerTick;
        frameStats.tlasBuildMilliseconds = double(ticks[4] - ticks[3]) * millisecondsPerTick;
      }
      if (wavefrontTracer) {
        std::vector<std::uint64_t> passTicks(wavefrontTimestamps);
        readTimestamps(kFirstWavefrontTimestamp, wavefrontTimestamps, passTicks.data());
        wavefrontTracer->addPassTimes(passTicks, settings.pathsPerPixel, settings.raysPerPath,
                                      millisecondsPerTick, frameStats);
      }
    }
    frameStats.cullingHostMilliseconds += look.cullingHostMilliseconds;
    if (look.looks) {
      frameStats.looks = 1;
      frameStats.lookMilliseconds = look.lookMilliseconds;
      frameStats.lookRays = look.lookRays;
      frameStats.gpuMilliseconds += look.lookMilliseconds;
      frameStats.blasBuilds += look.blasBuilds;
      frameStats.blasUpdates += look.blasUpdates;
      frameStats.blasEvictions += look.blasEvictions;
      frameStats.blasBuildMilliseconds += look.blasBuildMilliseconds;
      frameStats.tlasBuildMilliseconds += look.tlasBuildMilliseconds;
      frameStats.blasBytes = std::max(frameStats.blasBytes, look.blasBytes);
      frameStats.asScratchBytes = std::max(frameStats.asScratchBytes, look.asScratchBytes);
    }
    if (dynamicAccel) {
      // The render's figures: the peak of what was resident.
      auto& a = stats.accelerationStructures;
      a.blasBytes = std::max(a.blasBytes, frameStats.blasBytes);
      a.tlasBytes = frameStats.tlasBytes;
      a.scratchBytes = std::max(a.scratchBytes, frameStats.asScratchBytes);
      a.buildMilliseconds += frameStats.blasBuildMilliseconds + frameStats.tlasBuildMilliseconds;
    }
    stats.frames.push_back(frameStats);
    if (settings.onFrame)
      settings.onFrame(frameStats);
    ++sampleIndex;
    if (settings.continueAfterFrame && !settings.continueAfterFrame(frameStats))
      break;  // the image is the accumulation of the frames rendered so far
  }

  if (dynamicAccel) {
    result.instanceStates = dynamicAccel->culling().states();
    if (options_.debugCullingSize > 0)
      result.cullingView =
          cullingTopView(dynamicAccel->culling(), previousCamera, options_.debugCullingSize);
  }

  // Read the accumulated image back.
  GpuBuffer readback = hostBuffer(context, accumulationBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  context.submitAndWait([&](VkCommandBuffer commands) {
    VkBufferCopy copy{0, 0, accumulationBytes};
    vkCmdCopyBuffer(commands, accumulation.buffer(), readback.buffer(), 1, &copy);
  });
  result.image.width = settings.width;
  result.image.height = settings.height;
  result.image.rgba.resize(pixelCount * 4);
  readback.read(result.image.rgba.data(), accumulationBytes);
  return result;
}

}  // namespace memograph::runtime
