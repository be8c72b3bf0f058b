#include "runtime/trace/render_setup.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include <glm/glm.hpp>

#include "runtime/memo/material_cache.h"
#include "runtime/scene/camera_range.h"
#include "runtime/scene/scene_limits.h"
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
  if (s.firstFrame > std::numeric_limits<std::uint32_t>::max() - s.frames)
    throw std::invalid_argument("the last frame's index is past 2^32 - 1");
}

std::string megabytes(std::uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

SceneBufferBudget sceneBufferBudget(const DeviceInfo& info) {
  return SceneBufferBudget{info.name, info.limits.maxStorageBufferRange,
                           info.maxMemoryAllocationSize};
}

std::function<void(std::uint64_t, std::uint64_t)> deviceGeometryCheck(
    std::function<std::optional<DeviceInfo>()> peek) {
  // Every Vulkan device binds a storage buffer of 2^27 bytes and allocates 2^30 (the least
  // maxStorageBufferRange and maxMemoryAllocationSize the specification allows), so geometry
  // within them needs no device to check it. The device is asked once a buffer passes them,
  // and only then: a render of a smaller scene creates one Vulkan instance, the renderer's,
  // not a second one before it that loads the driver again (the first frame's wall time).
  constexpr std::uint64_t kEveryDevicesStorageRange = std::uint64_t(1) << 27;
  struct Device {
    std::function<std::optional<DeviceInfo>()> peek;
    bool asked = false;
    std::optional<SceneBufferBudget> budget;
  };
  auto device = std::make_shared<Device>(Device{std::move(peek)});
  return [device](std::uint64_t vertices, std::uint64_t triangles) {
    const std::uint64_t largest =
        std::max(vertices * sizeof(gpu::Vertex), triangles * 3 * sizeof(std::uint32_t));
    if (largest <= kEveryDevicesStorageRange)
      return;
    if (!device->asked) {
      device->asked = true;
      if (const std::optional<DeviceInfo> info = device->peek())
        device->budget = sceneBufferBudget(*info);
    }
    if (device->budget)  // none where no device qualifies: the renderer then says why
      checkGeometryBuffers(*device->budget, vertices, triangles, true);
  };
}

std::function<void(std::uint64_t, std::uint64_t)> deviceGeometryCheck(
    const ContextOptions& options) {
  return deviceGeometryCheck([options] { return peekDeviceInfo(options); });
}

namespace {

// A buffer of the scene refused where the device cannot hold it: past the largest allocation
// or, bound whole as a storage buffer, past maxStorageBufferRange. A SceneLimitError (exit
// 1): the scene is too large for this device, the request itself is sound.
void checkSceneBuffer(const VulkanContext& context, std::uint64_t bytes, const std::string& what,
                      const std::string& counted, bool storageBinding) {
  checkSceneBuffer(sceneBufferBudget(context.info()), bytes, what, counted, storageBinding);
}

// The device's largest device-local heap (on a CPU device, the host memory it may use).
std::uint64_t deviceLocalHeapBytes(const VulkanContext& context) {
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(context.physicalDevice(), &memory);
  std::uint64_t largest = 0;
  for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h)
    if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      largest = std::max<std::uint64_t>(largest, memory.memoryHeaps[h].size);
  return largest;
}

// The scene against the fixed limits (scene_limits.h) and this device, from the Scene's
// counts and the driver's own BLAS/TLAS size queries: a scene the device cannot hold is
// refused in milliseconds, before a material is linked or a byte uploaded, instead of after
// minutes and gigabytes in the driver. Throws SceneLimitError.
void checkSceneFitsDevice(const Scene& scene, const VulkanContext& context,
                          const CullingOptions& culling) {
  const SceneFootprint f = measureScene(scene);
  checkSceneLimits(f);
  const DeviceInfo& info = context.info();
  checkGeometryBuffers(sceneBufferBudget(info), f.vertices, f.triangles);
  checkSceneBuffer(context, f.instanceBytes, "instance buffer",
                   std::to_string(f.instances) + " instances of " +
                       std::to_string(sizeof(gpu::Instance)) + " bytes",
                   true);
  checkSceneBuffer(context, f.lightBytesAtMost, "light buffer",
                   std::to_string(f.lights) +
                       " lights and the triangles of its emitting instances, " +
                       std::to_string(sizeof(gpu::Light)) + " bytes each",
                   true);
  checkSceneBuffer(context, f.environmentBytes, "environment image",
                   std::to_string(f.environmentTexels) + " texels of 16 bytes", true);

  // The acceleration structures: the driver's sizes for each mesh's BLAS (the query needs
  // only counts, no buffers), and the TLAS over every instance.
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &as;
  vkGetPhysicalDeviceProperties2(context.physicalDevice(), &properties);
  if (as.maxInstanceCount > 0 && f.instances > as.maxInstanceCount)
    throw SceneLimitError("the scene has " + std::to_string(f.instances) +
                          " instances, more than the " + std::to_string(as.maxInstanceCount) +
                          " a top-level acceleration structure of " + info.name +
                          " may hold (maxInstanceCount)");
  if (as.maxPrimitiveCount > 0 && f.largestMeshTriangles > as.maxPrimitiveCount)
    throw SceneLimitError("a mesh of the scene has " + std::to_string(f.largestMeshTriangles) +
                          " triangles, more than the " + std::to_string(as.maxPrimitiveCount) +
                          " one acceleration structure of " + info.name +
                          " may hold (maxPrimitiveCount)");
  const DeviceFunctions& functions = context.functions();
  if (!functions.getAccelerationStructureBuildSizes)
    return;
  const VkDeviceSize alignment = info.minAccelerationStructureScratchOffsetAlignment;
  std::uint64_t blasBytes = 0, scratchBytes = 0, largestScratch = 0;
  for (const Mesh& mesh : scene.meshes) {
    VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    g.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
    g.geometry.triangles = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
    g.geometry.triangles.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    g.geometry.triangles.vertexStride = sizeof(gpu::Vertex);
    g.geometry.triangles.maxVertex =
        mesh.positions.empty() ? 0 : static_cast<std::uint32_t>(mesh.positions.size() - 1);
    g.geometry.triangles.indexType = VK_INDEX_TYPE_UINT32;
    VkAccelerationStructureBuildGeometryInfoKHR build{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    build.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                  VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR;
    build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    build.geometryCount = 1;
    build.pGeometries = &g;
    const std::uint32_t triangles = static_cast<std::uint32_t>(mesh.indices.size() / 3);
    VkAccelerationStructureBuildSizesInfoKHR sizes{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    functions.getAccelerationStructureBuildSizes(context.device(),
                                                 VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR,
                                                 &build, &triangles, &sizes);
    blasBytes += sizes.accelerationStructureSize;
    largestScratch = std::max<std::uint64_t>(largestScratch, sizes.buildScratchSize);
    scratchBytes += (sizes.buildScratchSize + alignment - 1) / alignment * alignment;
  }
  // The static set builds every BLAS in one batch with one scratch buffer (one allocation);
  // culling builds them a budget at a time, each with at most the largest scratch.
  const bool oneBatch = culling.mode == CullingMode::None;
  checkSceneBuffer(context, oneBatch ? scratchBytes : largestScratch,
                   "acceleration-structure build scratch",
                   std::to_string(f.meshes) + " meshes, " + std::to_string(f.triangles) +
                       " triangles, as the driver sizes their BLAS builds",
                   false);
  // Everything the scene puts on the device at once, against the device-local heap: the
  // buffers, the BLASes before compaction and, for the static set, their build scratch.
  const std::uint64_t total = f.vertexBytes + f.indexBytes + f.instanceBytes + f.meshBytes +
                              f.lightBytesAtMost + f.environmentBytes + blasBytes +
                              (oneBatch ? scratchBytes : largestScratch);
  const std::uint64_t heap = deviceLocalHeapBytes(context);
  if (heap > 0 && total > heap)
    throw SceneLimitError(
        "the scene needs about " + megabytes(total) + " of device memory (" +
        megabytes(f.vertexBytes + f.indexBytes) + " geometry, " + megabytes(blasBytes) +
        " acceleration structures, " + megabytes(oneBatch ? scratchBytes : largestScratch) +
        " build scratch), more than the " + megabytes(heap) + " device-local heap of " + info.name);
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
ShadingChoice chooseShading(const RendererOptions& options, const VulkanContext& context) {
  ShadingDevice device;
  device.type = context.info().type;
  device.wavefrontTraces =
      context.backend() == Backend::RayQuery || context.info().traceRaysIndirect;
  ShadingChoice shading = resolveShading(options, device);
  if (options.wavefrontPaths > 0 && shading.shading != Shading::Wavefront)
    throw std::invalid_argument(
        "--wavefront-paths sets the wavefront's paths in flight; it needs the wavefront, which "
        "--shading auto did not choose: " +
        shading.whyMegakernel + " (--shading wavefront asks for it)");
  if (options.shading == Shading::Wavefront) {
    const std::string gap = wavefrontGap(options, device);
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
  if (plan.dispatch != MaterialDispatch::Switch || options.floorMaterials ||
      options.integrator == Integrator::AmbientOcclusion || plan.wavefront ||
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
                             const Scene& scene) {
  validateSettings(settings);
  validateScene(scene);
  // The cameras, before anything is built for them: a camera far outside float range would
  // otherwise surface as a degenerate basis at the first frame. std::invalid_argument, as the
  // frame loop's own camera checks (a request the caller can fix).
  if (const std::string problem = cameraProblem(scene.camera);
      !problem.empty() && settings.cameraPath.empty())
    throw std::invalid_argument(problem);
  for (std::size_t k = 0; k < settings.cameraPath.size(); ++k)
    if (const std::string problem = cameraProblem(settings.cameraPath[k]); !problem.empty())
      throw std::invalid_argument("camera path frame " + std::to_string(k) + ": " + problem);
  validateCullingOptions(options.culling);
  const std::uint32_t pathWeight =
      options.culling.mode == CullingMode::Lipac
          ? feedbackPathWeight(options.culling.feedbackPaths, settings.pathsPerPixel)
          : 1;
  validateWavefrontOptions(options);
  validateIntegratorOptions(options);
  if (options.debugCullingSize > 0 && options.culling.mode == CullingMode::None)
    throw std::invalid_argument(
        "--debug-culling shows which instances culling keeps; it needs --culling frustum or "
        "--culling lipac");
  return pathWeight;
}

void validateRenderOnDevice(const RendererOptions& options, const Scene& scene,
                            const VulkanContext& context) {
  checkSceneFitsDevice(scene, context, options.culling);
  if (options.culling.blasBuildMilliseconds > 0.0 && !context.info().timestamps)
    throw std::invalid_argument(
        "--blas-build-ms times the BLAS builds with GPU timestamps, which this device does not "
        "have; --blas-build-budget limits the triangles built instead");
}

RenderPlan planRender(const RendererOptions& options, const RenderSettings& settings,
                      const VulkanContext& context, const SceneMaterials& materials,
                      std::uint32_t feedbackPathWeight) {
  RenderPlan plan;
  plan.feedbackPathWeight = feedbackPathWeight;
  plan.shading = chooseShading(options, context);
  plan.wavefront = plan.shading.shading == Shading::Wavefront;
  // The image is one storage buffer of 4 floats a pixel: refused before anything compiles
  // when the device cannot bind it whole.
  plan.accumulationBytes = std::uint64_t(settings.width) * settings.height * sizeof(glm::vec4);
  checkBufferSize(context, plan.accumulationBytes,
                  "a " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                      " image (16 bytes a pixel)",
                  true);
  // The textures the linked graphs read, each an image in one array binding: refused before
  // any is loaded (their texels are counted as they load, uploadSceneResources).
  const std::uint64_t textures = materials.linked.texturePaths.size();
  checkTextureLimits(textures, 0);
  const std::uint32_t sampledImages =
      std::min(context.info().limits.maxPerStageDescriptorSampledImages,
               context.info().limits.maxDescriptorSetSampledImages);
  if (textures > sampledImages)
    throw SceneLimitError("the scene's materials read " + std::to_string(textures) +
                          " textures, more than the " + std::to_string(sampledImages) +
                          " sampled images " + context.info().name +
                          " binds in one shader stage (maxPerStageDescriptorSampledImages)");
  plan.dispatch = resolveMaterialDispatch(options.materialDispatch, context.backend());
  plan.cache = resolveRenderCache(options, settings, context, plan.wavefront);
  checkCpuSwitchLimit(options, context, plan, materials.linked.distinct.size());
  return plan;
}

RenderStats::CachedCostShare cachedCostShare(const RendererOptions& options, const Scene& scene,
                                             const SceneMaterials& materials,
                                             const RenderPlan& plan) {
  RenderStats::CachedCostShare share;
  if (options.cache.mode == CacheMode::None || options.floorMaterials || scene.instances.empty())
    return share;
  // Cuts are keyed by the texel cache where the material runs as cut and rest: the
  // megakernel's switch and the wavefront (docs/design/memoization.md, "Keys of the cut").
  const bool keysCuts = options.cache.mode == CacheMode::Texel &&
                        (plan.wavefront || plan.dispatch == MaterialDispatch::Switch);
  // Every instance weighs by its graph's estimated cost: the share is of the scene's cost.
  double total = 0.0;
  for (const Instance& instance : scene.instances) {
    const LinkedMaterial& material = materials.linked.materials[instance.material];
    const double cost = material.estimatedCost;
    total += cost;
    if (material.cacheable)
      share.whole += cost;
    else if (keysCuts && material.cutDomain == gpu::kCacheCutUv)
      share.uv += cost * material.cutCostShare;
    else if (keysCuts && material.cutDomain == gpu::kCacheCutObject)
      share.object += cost * material.cutCostShare;
    else if (keysCuts && material.cutDomain == gpu::kCacheCutWorld)
      share.world += cost * material.cutCostShare;
  }
  if (total <= 0.0)
    return RenderStats::CachedCostShare{};
  share.whole /= total;
  share.uv /= total;
  share.object /= total;
  share.world /= total;
  return share;
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
  // The AO integrator evaluates no graph either: its stats name it in the dispatch's place.
  const bool ambientOcclusion = options.integrator == Integrator::AmbientOcclusion;
  stats.materialDispatch = ambientOcclusion ? "ao"
                           : floor          ? "floor"
                           : plan.wavefront ? "batched"
                                            : materialDispatchName(plan.dispatch);
  stats.cachedCostShare = cachedCostShare(options, scene, materials, plan);
  return stats;
}

}  // namespace memograph::runtime
