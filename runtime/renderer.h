// The runtime's front door: renders a runtime::Scene with the thesis §5.2 path tracer into
// an HDR float image and reports per-frame statistics. Needs only Vulkan, glslang (static)
// and GLM; image and scene files are the callers' business (tools/, the scenes module).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runtime/accel/scene_culling.h"
#include "runtime/host/image.h"
#include "runtime/materials/material_linker.h"
#include "runtime/memo/cache_options.h"
#include "runtime/scene/scene.h"
#include "runtime/trace/integrator.h"
#include "runtime/trace/render_stats.h"
#include "runtime/trace/shading.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

// Loads the texture a material graph names (path resolved against the graph's folder).
// Throws std::runtime_error naming the path when it cannot.
using TextureLoader = std::function<TextureImage(const std::string& path)>;

// The core's own loader: PFM files only (no OpenImageIO in the core); anything else gets an
// error that says which tool can convert it.
TextureImage loadTextureCore(const std::string& path);

// Scenes with more distinct material graphs than this render best with per-material callable
// shaders: one shader holding every graph grows too large to compile quickly (the CLI makes
// `--backend auto` pick the pipeline backend for them). 8, not more: the city's 14 graphs
// in one query shader ran lavapipe's compiler past 16 minutes and 13 GB before it was
// stopped, where their 14 callables took 26 s.
constexpr std::size_t kManyMaterialGraphs = 8;

struct RendererOptions {
  ContextOptions context;
  // The SPIR-V cache, and the device's pipeline cache file in the same folder
  // (runtime/vk/pipeline_cache.h); false: neither.
  bool shaderCache = true;
  std::filesystem::path shaderCacheDirectory;  // empty: defaultShaderCacheDirectory()
  std::filesystem::path nodeLibraryDirectory;  // empty: the embedded node library
  TextureLoader textureLoader = loadTextureCore;
  // Auto: a callable shader per material on the pipeline backend (no shader holds every
  // graph), the switch on the query backend (compute shaders have no callables).
  MaterialDispatch materialDispatch = MaterialDispatch::Auto;
  // On a CPU device (lavapipe) a switch over more distinct materials than this is refused
  // before compiling: llvmpipe compiles the one shader in about 110 MB per material (the
  // 88-material classroom: over 12 GB). 0: no limit.
  // Twice kManyMaterialGraphs: `--backend auto` already avoids the switch above that, and an
  // explicit `--backend query` on, say, the showcase's 14 graphs works (44.8 s on lavapipe).
  std::uint32_t cpuSwitchMaterialLimit = 2 * kManyMaterialGraphs;
  // Threads compiling callable material shaders and joining the driver's ray-tracing
  // pipeline compile (deferred host operations); 0: one per hardware thread.
  std::uint32_t shaderCompileThreads = 0;
  CacheOptions cache;  // cleared at the start of every render
  // The floor run: every material replaced by constants (a base colour per material id,
  // roughness 0.5, metallic 0, the geometric normal) and no graph evaluated, for the cost
  // of a free material. Stats say materialDispatch "floor". Not with a cache.
  bool floorMaterials = false;
  // Wavefront: no culling, debug view or animated meshes, and a cache only with the scene's
  // graphs (checked by validateWavefrontOptions and render()); the tile cache fills through
  // the deferred fill's queue only. Auto: resolved per render by resolveShading.
  Shading shading = Shading::Auto;
  // The wavefront's paths in flight (its path state's capacity); a round over more pixels
  // runs in chunks of this many. 0: every pixel, or what the device's storage-buffer range
  // holds. Non-zero needs the wavefront (Shading::Wavefront, or Auto resolving to it).
  std::uint32_t wavefrontPaths = 0;
  // Wavefront: graphs of one shape (equal but for float constants) share a material pass
  // (LinkedMaterials::instanceGroups). False only to check that sharing changes no picture.
  bool materialInstances = true;
  // With materialInstances: the first frame renders with the shared passes, and each graph
  // of a shared pass gets its own before the second frame (a shared pass starts sooner; on an
  // H100 the classroom's 88 own passes ran 12.1 ms a frame against the 11 shared ones' 14.9).
  // Unset: on GPUs, not on CPU devices (lavapipe), whose driver compile is the cost.
  std::optional<bool> ownMaterialPassesFromSecondFrame;
  // The megakernel: a frame's P paths per pixel are traced in dispatches of at most this many
  // paths each (runtime/trace/megakernel/path_dispatches.h); 0: all P in one. The default is the
  // fastest split measured: at P = 6 (5 paths, then 1) the unculled city's frame took 0.935x the
  // time of one dispatch on an H100 (docs/design/path-tracer.md, "Paths per dispatch"); P <= 5
  // stays one dispatch. The wavefront ignores it: its rounds trace one path of every pixel each
  // already.
  std::uint32_t pathsPerDispatch = 5;
  // Thesis Fig. 6.9: the image shows each frame alone, pixels where a path missed the
  // cache in red. Needs the texel cache.
  bool debugCacheMisses = false;
  // Culled acceleration structures (seeds/001 §3.3): which instances the TLAS holds each
  // frame, and the BLAS budgets. None: every instance, all BLASes built up front.
  CullingOptions culling;
  // Culled renders: also draw cullingTopView of the last frame, this many pixels a side
  // (RenderResult::cullingView; 0: none).
  std::uint32_t debugCullingSize = 0;
  // What a pixel holds: the path tracer's radiance, or the ray-traced AO workload's
  // unoccluded fraction (seeds/004 §3; runtime/trace/integrator.h; auto runs it in the
  // megakernel).
  Integrator integrator = Integrator::Path;
  AmbientOcclusionOptions ambientOcclusion;  // Integrator::AmbientOcclusion's rays
  // Cycles' Filter Glossy (F >= 0, finite; 0: off): replaces the scene's Scene::filterGlossy
  // where set (--filter-glossy).
  std::optional<float> filterGlossy;
};

// Materials that share a graph (same file or same text) count once.
std::size_t countDistinctMaterialGraphs(const Scene& scene);

struct RenderSettings {
  std::uint32_t width = 64;
  std::uint32_t height = 64;
  std::uint32_t pathsPerPixel = 1;  // P
  std::uint32_t raysPerPath = 2;    // L: rays per path (1 = primary ray + direct light only)
  std::uint32_t frames = 1;
  // The index of the first frame rendered: frames firstFrame..firstFrame+frames-1, each
  // with its own camera of the path, clocks and random numbers, so that a range of a path
  // rendered alone traces what the same frames of the whole path trace.
  std::uint32_t firstFrame = 0;
  // Every frame starts its pixels' means afresh, even where the camera stays: a frame of a
  // frame range is an image of its own, the same whichever frames were rendered before it.
  bool eachFrameAlone = false;
  std::uint32_t seed = 0;
  bool sharedPrimaryRay = false;  // one primary ray through the pixel centre for all P paths
  // One camera per frame (the last repeats); empty: the scene's camera. Accumulation
  // restarts whenever the camera moves.
  std::vector<Camera> cameraPath;
  float secondsPerFrame = 1.0f / 30.0f;  // MaterialInputs::time advances by this per frame
  std::function<void(const FrameStats&)> onFrame;  // progress reporting
  // Asked after each frame; false ends the render there (RenderStats::frames then holds
  // fewer than `frames`), e.g. a benchmark's time limit.
  std::function<bool(const FrameStats&)> continueAfterFrame;
  // Asked before each frame; true: the frame's image is read back after it and handed to
  // onFrameImage (a frame range's outputs; warm-up frames and finished ones are not).
  std::function<bool(std::uint32_t frame)> frameImageWanted;
  // Asked before each frame; true: the frame is not rendered at all. Only for frames whose
  // state nothing later needs (a resumed frame range's finished frames without a cache or
  // LiPaC, each frame alone); never the first frame of the render.
  std::function<bool(std::uint32_t frame)> skipFrame;
  std::function<void(std::uint32_t frame, const HdrImage&)> onFrameImage;
  // Before the render's first frame, and again after the pipelines created before its second,
  // a GPU (not a CPU device) runs a compute pass that only spins, for this many milliseconds
  // (ClockWarmup): a discrete GPU lowers its clocks while it idles through host work, and
  // its first frames would otherwise time the clocks. 0: none. `memograph bench` sets it.
  std::uint32_t clockWarmupMilliseconds = 0;
};

struct RenderResult {
  HdrImage image;  // the accumulated mean radiance of the last camera's frames
  RenderStats stats;
  // Culled renders: each instance's state in the last frame, and its top view when asked
  // (RendererOptions::debugCullingSize).
  std::vector<InstanceState> instanceStates;
  // With mesh LODs, each instance's LOD when last in the TLAS (docs/design/culling.md).
  std::vector<std::uint8_t> instanceLods;
  HdrImage cullingView;
};

class Renderer {
 public:
  explicit Renderer(RendererOptions options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The device. The constructor creates it on a thread of its own (a GPU driver's start
  // takes hundreds of milliseconds), so render() links the scene's materials meanwhile; the
  // first call waits for it, and every call rethrows what its creation threw.
  const VulkanContext& context() const { return *context_.get(); }

  // Compiles the scene's materials, uploads it, builds its acceleration structures and
  // renders settings.frames frames. Throws std::runtime_error / std::invalid_argument with a
  // message for people on bad input, VulkanError on device failures.
  RenderResult render(const Scene& scene, const RenderSettings& settings);

 private:
  RendererOptions options_;
  std::shared_future<std::unique_ptr<VulkanContext>> context_;
};

}  // namespace memograph::runtime
