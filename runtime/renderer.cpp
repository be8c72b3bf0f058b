#include "runtime/renderer.h"

#include <chrono>
#include <cmath>
#include <future>
#include <set>
#include <stdexcept>

#include "runtime/accel/render_acceleration.h"
#include "runtime/materials/scene_materials.h"
#include "runtime/scene/scene_resources.h"
#include "runtime/trace/frame_loop.h"
#include "runtime/trace/render_pipelines.h"
#include "runtime/trace/render_setup.h"
#include "runtime/vk/shader_compiler.h"

namespace memograph::runtime {

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

std::size_t countDistinctMaterialGraphs(const Scene& scene) {
  std::set<std::pair<std::string, std::string>> graphs;
  for (const auto& material : scene.materials) {
    graphs.emplace(material.graphPath, material.graphText);
  }
  return graphs.size();
}

namespace {

// Where compiled shaders and the device's pipeline cache are kept (none without the cache).
std::filesystem::path cacheDirectory(const RendererOptions& options) {
  if (!options.shaderCache)
    return {};
  return options.shaderCacheDirectory.empty() ? defaultShaderCacheDirectory()
                                              : options.shaderCacheDirectory;
}

ContextOptions contextOptions(const RendererOptions& options) {
  ContextOptions context = options.context;
  context.pipelineCacheDirectory = cacheDirectory(options);
  return context;
}

}  // namespace

Renderer::Renderer(RendererOptions options)
    : options_(std::move(options)),
      context_(std::async(std::launch::async, [context = contextOptions(options_)] {
        return std::make_unique<VulkanContext>(context);
      })) {}

Renderer::~Renderer() = default;

// The stages in order, each refusing bad input before the next spends time on it: the
// request checked; the materials linked (the graphs, and whether NEE must evaluate an
// emitter's), while the constructor's thread still creates the device; the request checked
// against the device; the plan (architecture, dispatch, cache); the scene and its
// textures uploaded; the acceleration structures built; the shaders compiled into the chosen
// architecture's pipelines; then the frames.
RenderResult Renderer::render(const Scene& scene, const RenderSettings& settings) {
  const auto renderStart = std::chrono::steady_clock::now();
  const std::uint32_t pathWeight = validateRender(options_, settings, scene);
  const SceneMaterials materials =
      linkSceneMaterials(scene, options_.nodeLibraryDirectory, options_.cache.keyDomains);
  const VulkanContext& context = this->context();
  validateRenderOnDevice(options_, scene, context);
  const RenderPlan plan = planRender(options_, settings, context, materials, pathWeight);
  RenderResult result;
  result.stats = describeRender(options_, settings, scene, context, materials, plan);

  const std::filesystem::path shaderCacheDirectory = cacheDirectory(options_);
  PipelineCache& pipelineCache = context.pipelineCache();
  const PipelineCacheCounts countsBefore = pipelineCache.counts();

  SceneResources resources =
      uploadSceneResources(context, scene, materials.emissionKinds, materials.linked.texturePaths,
                           options_.textureLoader);
  result.stats.textureBytes = resources.textures->bytes();
  // The mesh LODs' distance choice needs a pixel's angle (CullingOptions::imageHeight).
  CullingOptions culling = options_.culling;
  culling.imageHeight = settings.height;
  RenderAcceleration acceleration(context, scene, resources.buffers, culling, shaderCacheDirectory,
                                  pathWeight, result.stats);

  PipelineInputs pipelineInputs;
  pipelineInputs.materials = &materials;
  pipelineInputs.scene = &resources;
  pipelineInputs.hitFeedback = acceleration.hitFeedbackOn();
  pipelineInputs.shaderCacheDirectory = shaderCacheDirectory;
  pipelineInputs.ambientOcclusionDistance =
      resolveAmbientOcclusionDistance(options_.ambientOcclusion, scene);
  pipelineInputs.filterGlossy = options_.filterGlossy.value_or(scene.filterGlossy);
  if (!(pipelineInputs.filterGlossy >= 0.0f) || !std::isfinite(pipelineInputs.filterGlossy))
    throw std::invalid_argument("Filter Glossy must be a finite number >= 0, not " +
                                std::to_string(pipelineInputs.filterGlossy));
  if (options_.integrator == Integrator::AmbientOcclusion) {
    result.stats.ambientOcclusionSamples = options_.ambientOcclusion.samples;
    result.stats.ambientOcclusionDistance = pipelineInputs.ambientOcclusionDistance;
  }
  const RenderPipelines pipelines =
      buildPipelines(context, options_, settings, plan, pipelineInputs, result.stats);
  // Every pipeline of the render exists now (the animated meshes' pass too): the driver's
  // cache is written back before the frames, so a render that fails later still leaves it.
  const PipelineCacheCounts countsAfter = pipelineCache.counts();
  result.stats.pipelinesCreated = countsAfter.created - countsBefore.created;
  result.stats.pipelineCacheHitsReported = countsAfter.reported > countsBefore.reported;
  result.stats.pipelineCacheHits = countsAfter.hits - countsBefore.hits;
  result.stats.pipelineCreateCallMilliseconds =
      double(countsAfter.creationNanoseconds - countsBefore.creationNanoseconds) / 1e6;
  result.stats.pipelineCacheLoadedBytes = pipelineCache.loadedBytes();
  result.stats.pipelineCacheWritten = pipelineCache.save();

  FrameLoopInputs frames;
  frames.scene = &scene;
  frames.settings = &settings;
  frames.culling = &options_.culling;
  frames.plan = &plan;
  frames.resources = &resources;
  frames.acceleration = &acceleration;
  frames.cache = pipelines.cache.get();
  frames.tracer = pipelines.tracer.get();
  frames.shaderCacheDirectory = shaderCacheDirectory;
  frames.cullingViewSize = options_.debugCullingSize;
  frames.renderStart = renderStart;
  FrameLoop(context, frames).run(result);
  if (result.stats.deferredPipelinesCreated > 0) {
    // The graphs' own material passes, created before the second frame, join the file too.
    result.stats.deferredPipelineCacheHits = pipelineCache.counts().hits - countsAfter.hits;
    result.stats.pipelineCacheWritten = pipelineCache.save() || result.stats.pipelineCacheWritten;
  }
  return result;
}

}  // namespace memograph::runtime
