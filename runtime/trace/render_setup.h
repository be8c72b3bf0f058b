// The first stages of Renderer::render: the request checked (validateRender); once the
// materials are linked, the request checked on the device (validateRenderOnDevice), then what
// the render will run (planRender: the architecture, the material dispatch, the cache's
// resolved options) and the statistics that describe it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "runtime/materials/scene_materials.h"
#include "runtime/memo/cache_options.h"
#include "runtime/renderer.h"
#include "runtime/scene/scene_limits.h"

namespace memograph::runtime {

// What the checks decided, for the stages after them.
struct RenderPlan {
  ShadingChoice shading;
  bool wavefront = false;
  MaterialDispatch dispatch = MaterialDispatch::Switch;
  CacheOptions cache;  // resolved for the device (resolveCacheOptions)
  // What a counted path's ray weighs in a LiPaC counting frame (CullingOptions::feedbackPaths:
  // P / N); 1 without LiPaC.
  std::uint32_t feedbackPathWeight = 1;
  std::uint64_t accumulationBytes = 0;  // the image: 4 floats a pixel
};

// The device's limits on one scene buffer (scene_limits.h), for checks of a scene against it.
SceneBufferBudget sceneBufferBudget(const DeviceInfo& info);

// The check a built-in scene runs while it is built (BuiltinSceneOptions::onGeometry):
// checkGeometryBuffers against the device a renderer with `options` would choose, read
// before the renderer exists (peekDeviceInfo) once the geometry passes what every Vulkan
// device holds. No check where no device qualifies; the renderer then says why.
std::function<void(std::uint64_t vertices, std::uint64_t triangles)> deviceGeometryCheck(
    const ContextOptions& options);
// The same with the device read by `peek`, called at most once.
std::function<void(std::uint64_t vertices, std::uint64_t triangles)> deviceGeometryCheck(
    std::function<std::optional<DeviceInfo>()> peek);

// The checks that need neither the materials nor the device: the settings, the scene, the
// cameras and the options. Returns the feedback path weight. Throws std::invalid_argument
// naming the option.
std::uint32_t validateRender(const RendererOptions& options, const RenderSettings& settings,
                             const Scene& scene);

// What the device cannot do for the request: the scene's size against its limits, and the
// options that need a feature it lacks. Throws as validateRender does.
void validateRenderOnDevice(const RendererOptions& options, const Scene& scene,
                            const VulkanContext& context);

// The architecture (resolveShading), then every check that needs it or the materials, before
// anything compiles: the image's buffer, the material dispatch, the cache on this device and
// the CPU's switch limit.
RenderPlan planRender(const RendererOptions& options, const RenderSettings& settings,
                      const VulkanContext& context, const SceneMaterials& materials,
                      std::uint32_t feedbackPathWeight);

// RenderStats::cachedCostShare: what the cache of `options` can serve of `scene`'s estimated
// material cost in the architecture `plan` chose.
RenderStats::CachedCostShare cachedCostShare(const RendererOptions& options, const Scene& scene,
                                             const SceneMaterials& materials,
                                             const RenderPlan& plan);

// The statistics known before the upload: the device, the image, the architecture, the
// materials and the culling mode.
RenderStats describeRender(const RendererOptions& options, const RenderSettings& settings,
                           const Scene& scene, const VulkanContext& context,
                           const SceneMaterials& materials, const RenderPlan& plan);

}  // namespace memograph::runtime
