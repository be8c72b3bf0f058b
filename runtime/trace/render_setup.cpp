#include "runtime/trace/render_setup.h"

#include <stdexcept>

#include <glm/glm.hpp>

#include "runtime/memo/material_cache.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/vk/gpu_buffer.h"

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

// The architecture the render runs, refused where the options ask what it cannot do.
ShadingChoice chooseShading(const RendererOptions& options, const Scene& scene,
                            const VulkanContext& context, bool neeEvaluatesEmission) {
  ShadingDevice device;
  device.type = context.info().type;
  device.wavefrontTraces =
      context.backend() == Backend::RayQuery || context.info().traceRaysIndirect;
  const ShadingChoice shading = resolveShading(options, scene, device, neeEvaluatesEmission);
  if (options.wavefrontPaths > 0 && shading.shading != Shading::Wavefront)
    throw std::invalid_argument(
        "--wavefront-paths sets the wavefront's paths in flight; it needs the wavefront, which "
        "--shading auto did not choose: " +
        shading.whyMegakernel + " (--shading wavefront asks for it)");
  if (options.shading == Shading::Wavefront) {
    const std::string gap = wavefrontGap(options, scene, device, neeEvaluatesEmission);
    if (!gap.empty())
      throw std::invalid_argument("--shading wavefront is a prototype: " + gap +
                                  " (--shading megakernel or auto)");
  }
  return shading;
}

// The cache's options resolved for this device and render, checked before minutes of
// material compiles.
CacheOptions resolveRenderCache(const RendererOptions& options, const RenderSettings& settings,
                                const VulkanContext& context, bool wavefront) {
  // The wavefront computes missing tiles in its material passes, from the deferred fill's
  // queue: there is no subgroup of lookups to share a tile's texels out (an explicit subgroup
  // fill is a wavefrontGap).
  CacheOptions requested = options.cache;
  if (wavefront && requested.mode == CacheMode::Tile)
    requested.tileFill = TileFill::Deferred;
  const CacheOptions cache = resolveCacheOptions(requested, context.info().bufferInt64Atomics,
                                                 std::uint64_t(settings.width) * settings.height *
                                                     settings.pathsPerPixel * settings.raysPerPath);
  const bool cacheOn = cache.mode != CacheMode::None;
  if (cacheOn) {
    validateCacheOptions(cache);
    validateCacheOnDevice(context, cache);
    if (cache.clock == CacheClock::Counter && !context.info().bufferInt64Atomics)
      throw std::runtime_error(
          "--clock counter needs 64-bit atomics on storage buffers "
          "(shaderInt64 and shaderBufferInt64Atomics), which " +
          context.info().name + " lacks; use --clock frame");
  }
  if (options.debugCacheMisses && !cacheOn)
    throw std::invalid_argument(
        "--debug-misses shows cache misses; it needs --cache texel or --cache tile");
  return cache;
}

// On a CPU device, a switch over more distinct materials than the limit fails in a second
// rather than after minutes and gigabytes of LLVM. The wavefront compiles each graph into a
// pipeline of its own: no switch to outgrow.
void checkCpuSwitchLimit(const RendererOptions& options, const VulkanContext& context,
                         const RenderPlan& plan, std::size_t distinctMaterials) {
  if (plan.dispatch != MaterialDispatch::Switch || options.floorMaterials || plan.wavefront ||
      context.info().type != VK_PHYSICAL_DEVICE_TYPE_CPU || options.cpuSwitchMaterialLimit == 0 ||
      distinctMaterials <= options.cpuSwitchMaterialLimit)
    return;
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
      std::to_string(options.cpuSwitchMaterialLimit) + ")");
}

}  // namespace

std::uint32_t validateRender(const RendererOptions& options, const RenderSettings& settings,
                             const Scene& scene, const VulkanContext& context) {
  validateSettings(settings);
  validateScene(scene);
  validateCullingOptions(options.culling);
  const std::uint32_t pathWeight =
      options.culling.mode == CullingMode::Lipac
          ? feedbackPathWeight(options.culling.feedbackPaths, settings.pathsPerPixel)
          : 1;
  validateWavefrontOptions(options);
  if (options.debugCullingSize > 0 && options.culling.mode == CullingMode::None)
    throw std::invalid_argument(
        "--debug-culling shows which instances culling keeps; it needs --culling frustum or "
        "--culling lipac");
  if (options.culling.blasBuildMilliseconds > 0.0 && !context.info().timestamps)
    throw std::invalid_argument(
        "--blas-build-ms times the BLAS builds with GPU timestamps, which this device does not "
        "have; --blas-build-budget limits the triangles built instead");
  return pathWeight;
}

RenderPlan planRender(const RendererOptions& options, const RenderSettings& settings,
                      const Scene& scene, const VulkanContext& context,
                      const SceneMaterials& materials, std::uint32_t feedbackPathWeight) {
  RenderPlan plan;
  plan.feedbackPathWeight = feedbackPathWeight;
  plan.shading = chooseShading(options, scene, context, materials.neeEvaluatesEmission);
  plan.wavefront = plan.shading.shading == Shading::Wavefront;
  // The image is one storage buffer of 4 floats a pixel: refused before anything compiles
  // when the device cannot bind it whole.
  plan.accumulationBytes = std::uint64_t(settings.width) * settings.height * sizeof(glm::vec4);
  checkBufferSize(context, plan.accumulationBytes,
                  "a " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                      " image (16 bytes a pixel)",
                  true);
  plan.dispatch = resolveMaterialDispatch(options.materialDispatch, context.backend());
  plan.cache = resolveRenderCache(options, settings, context, plan.wavefront);
  checkCpuSwitchLimit(options, context, plan, materials.linked.distinct.size());
  return plan;
}

RenderStats describeRender(const RendererOptions& options, const RenderSettings& settings,
                           const Scene& scene, const VulkanContext& context,
                           const SceneMaterials& materials, const RenderPlan& plan) {
  RenderStats stats;
  stats.device = context.info().name;
  stats.backend = backendName(context.backend());
  stats.width = settings.width;
  stats.height = settings.height;
  stats.pathsPerPixel = settings.pathsPerPixel;
  stats.raysPerPath = settings.raysPerPath;
  stats.materialCount = static_cast<std::uint32_t>(scene.materials.size());
  stats.materialCompileMilliseconds = materials.linked.compileMilliseconds;
  stats.culling = std::string(cullingModeName(options.culling.mode));
  stats.shading = shadingName(plan.shading.shading);
  const bool floor = options.floorMaterials;
  stats.materialDispatch = floor            ? "floor"
                           : plan.wavefront ? "batched"
                                            : materialDispatchName(plan.dispatch);
  return stats;
}

}  // namespace memograph::runtime
