// The runtime's front door: renders a runtime::Scene with the thesis §5.2 path tracer into
// an HDR float image and reports per-frame statistics. Needs only Vulkan, glslang (static)
// and GLM; image and scene files are the callers' business (tools/, the scenes module).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/image.h"
#include "runtime/material_linker.h"
#include "runtime/render_stats.h"
#include "runtime/scene.h"
#include "runtime/vulkan_context.h"

namespace memograph::runtime {

// Loads the texture a material graph names (path resolved against the graph's folder).
// Throws std::runtime_error naming the path when it cannot.
using TextureLoader = std::function<TextureImage(const std::string& path)>;

// The core's own loader: PFM files only (no OpenImageIO in the core); anything else gets an
// error that says which tool can convert it.
TextureImage loadTextureCore(const std::string& path);

// Material graph memoization (thesis §4, §5.3-5.4). Texel: one hash table of texels, keyed
// by material, mip level and texel (eq. 5.1-5.10), linear probing over `probe` entries.
// Tile: entries are tiles of texels, computed by a whole subgroup on a miss (§5.4.3).
enum class CacheMode { None, Texel, Tile };
// How a tile is sampled (§4.6, eq. 5.12-5.15): its nearest texel, or bilinearly from tiles
// that overlap by one texel.
enum class TileFilter { Nearest, Bilinear };
// Where a tile's texels live (§5.4.1). Values are the shader's kTileStorage*.
enum class TileStorage { Entry = 0, Buffer = 1, Texture2D = 2, Texture3D = 3 };
// What a miss evicts when its probe range is full (§4.5): none (insert only into empty
// entries), the least recently used or least recently written entry by a frame clock
// (§5.3.3), or a pseudo-random entry. Values are the shader's kCacheEviction*.
enum class CacheEviction { None = 0, Lru = 1, Lrw = 2, Random = 3 };

const char* cacheModeName(CacheMode mode);
const char* cacheEvictionName(CacheEviction eviction);
const char* tileFilterName(TileFilter filter);
const char* tileStorageName(TileStorage storage);
// Parse "none"/"texel" and "none"/"lru"/"lrw"/"random"; throw std::invalid_argument naming the
// choices.
CacheMode parseCacheMode(const std::string& text);
CacheEviction parseCacheEviction(const std::string& text);
// "nearest"/"bilinear" and "entry"/"buffer"/"texture2d"/"texture3d", likewise.
TileFilter parseTileFilter(const std::string& text);
TileStorage parseTileStorage(const std::string& text);

struct CacheOptions {
  CacheMode mode = CacheMode::None;
  std::uint32_t entries = 1u << 20;  // S; must exceed `probe`
  std::uint32_t probe = 8;           // D, 1..16 (gpu::kCacheMaxProbe)
  float mipBias = 0.0f;              // eq. 5.5; positive: finer texels
  CacheEviction eviction = CacheEviction::Lru;
  // §5.3.4: false checks a read by reading the key again (the thesis's choice, open to the
  // A-B-A race); true adds a per-entry update counter that closes it (one more uint per
  // entry and an atomic per write). Default to be picked from a GPU measurement.
  bool updateCounter = false;
  // Tile cache (§5.4): texels stored per tile (W x H <= the device's subgroup size; the
  // thesis's default 4 x 4 needs 16 lanes, lavapipe has 8), the filter, the storage and
  // §5.4.4's grouping of missing tiles by material. `entries` counts tiles.
  std::uint32_t tileWidth = 4;
  std::uint32_t tileHeight = 4;
  TileFilter tileFilter = TileFilter::Nearest;
  TileStorage tileStorage = TileStorage::Entry;
  bool groupByMaterial = false;
};

struct RendererOptions {
  ContextOptions context;
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
  std::uint32_t cpuSwitchMaterialLimit = 16;
  // Threads compiling callable material shaders and joining the driver's ray-tracing
  // pipeline compile (deferred host operations); 0: one per hardware thread.
  std::uint32_t shaderCompileThreads = 0;
  CacheOptions cache;  // cleared at the start of every render
};

// Scenes with more distinct material graphs than this render best with per-material callable
// shaders: one shader holding every graph grows too large to compile quickly (the CLI makes
// `--backend auto` pick the pipeline backend for them).
constexpr std::size_t kManyMaterialGraphs = 16;

// Materials that share a graph (same file or same text) count once.
std::size_t countDistinctMaterialGraphs(const Scene& scene);

struct RenderSettings {
  std::uint32_t width = 64;
  std::uint32_t height = 64;
  std::uint32_t pathsPerPixel = 1;  // P
  std::uint32_t raysPerPath = 2;    // L: rays per path (1 = primary ray + direct light only)
  std::uint32_t frames = 1;
  std::uint32_t seed = 0;
  bool sharedPrimaryRay = false;  // one primary ray through the pixel centre for all P paths
  // One camera per frame (the last repeats); empty: the scene's camera. Accumulation
  // restarts whenever the camera moves.
  std::vector<Camera> cameraPath;
  float secondsPerFrame = 1.0f / 30.0f;  // MaterialInputs::time advances by this per frame
  std::function<void(const FrameStats&)> onFrame;  // progress reporting
};

struct RenderResult {
  HdrImage image;  // the accumulated mean radiance of the last camera's frames
  RenderStats stats;
};

class Renderer {
 public:
  explicit Renderer(RendererOptions options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const VulkanContext& context() const { return *context_; }

  // Compiles the scene's materials, uploads it, builds its acceleration structures and
  // renders settings.frames frames. Throws std::runtime_error / std::invalid_argument with a
  // message for people on bad input, VulkanError on device failures.
  RenderResult render(const Scene& scene, const RenderSettings& settings);

 private:
  RendererOptions options_;
  std::unique_ptr<VulkanContext> context_;
};

}  // namespace memograph::runtime
