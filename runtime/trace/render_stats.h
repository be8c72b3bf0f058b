// What a render measured: per-frame GPU time (timestamp queries) and rays, set-up costs and
// acceleration-structure memory. The CLI writes it as CSV (--stats).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "runtime/accel/acceleration_structures.h"

namespace memograph::runtime {

// A new per-frame counter also goes into frameCounters() (frame_counters.cpp), which the
// bench summary reads.
struct FrameStats {
  std::uint32_t frame = 0;
  double gpuMilliseconds = 0.0;   // between the timestamps around the trace (0 if none)
  double wallMilliseconds = 0.0;  // submit to fence on the host
  std::uint64_t rays = 0;         // closest-hit and shadow rays traced
  // Texel cache counters (thesis §5.3): lookups of cacheable materials, hits and misses.
  std::uint64_t cacheLookups = 0;
  std::uint64_t cacheHits = 0;
  std::uint64_t cacheMisses = 0;
  // Entries in use (ever filled) after this frame: persists across frames, at most S.
  std::uint64_t cacheOccupancy = 0;
  // The counter clock after this frame (§5.3.3; 0 with the frame clock): never reset.
  std::uint64_t cacheClockTicks = 0;
  // Tile cache (§5.4.3, §6.7.2): tiles the subgroups computed, how many of those had been
  // computed already this frame, and misses that evaluated their own hit instead (too few
  // active lanes; or a repack across a callable).
  std::uint64_t cacheTilesComputed = 0;
  std::uint64_t cacheDuplicateTiles = 0;
  std::uint64_t cacheTileFallbacks = 0;
  std::uint64_t cacheTileRepacks = 0;
  // Inserts' locks (both caches): chosen beside a locked entry of the probe range, and lost
  // to another invocation's lock (gpu::Counters).
  std::uint64_t cacheLocksBesideALock = 0;
  std::uint64_t cacheLocksContended = 0;
  // Tiles published (their key written after their last texel) since the cache was cleared:
  // persists across frames like the occupancy. Not in the CSV.
  std::uint64_t cacheTilesPublished = 0;
  // Acceleration structures this frame (seeds/001 §3.3; with --culling none the scene's
  // static set): instances in the TLAS, omitted (a counting box stands in), inactive, and
  // active ones still waiting for their BLAS (the build budget); LiPaC's hitboxes (with
  // instances) and how many are active; instance state changes in this frame's update;
  // TLAS records (instances and boxes); resident BLAS and TLAS bytes, and scratch (the
  // TLAS's, the animated BLASes', this frame's BLAS builds'); BLAS builds (rebuilds of
  // animated ones included), in-place updates and evictions; GPU build times (BLAS: builds,
  // updates and the moved vertices' copies).
  std::uint32_t activeInstances = 0;
  std::uint32_t omittedInstances = 0;
  std::uint32_t inactiveInstances = 0;
  std::uint32_t waitingInstances = 0;
  std::uint32_t hitboxes = 0;
  std::uint32_t activeHitboxes = 0;
  std::uint32_t instanceStateChanges = 0;
  // LiPaC's looks before this frame (0 or 1: SceneCulling::look), the GPU time of the look's
  // probe trace, which gpuMilliseconds includes, and the rays it traced (not in `rays`).
  std::uint32_t looks = 0;
  double lookMilliseconds = 0.0;
  std::uint64_t lookRays = 0;
  // 1 where this frame's trace counted (LiPaC's feedback pipeline: --feedback-every), so that
  // the frames that count and those that do not can be timed apart.
  std::uint32_t feedbackFrame = 0;
  // The megakernel's trace dispatches this frame (planPathDispatches; 0: the wavefront's).
  std::uint32_t traceDispatches = 0;
  std::uint32_t tlasRecords = 0;
  std::uint64_t blasBytes = 0;
  std::uint64_t tlasBytes = 0;
  std::uint64_t asScratchBytes = 0;
  std::uint32_t blasBuilds = 0;
  std::uint32_t blasUpdates = 0;  // animated meshes' BLASes updated in place
  std::uint32_t blasEvictions = 0;
  double blasBuildMilliseconds = 0.0;
  double tlasBuildMilliseconds = 0.0;
  // Host time of the frame's culling: reading the counters, the state update and writing
  // the TLAS records (what §3.3.2 runs in compute passes); BLAS builds excluded.
  double cullingHostMilliseconds = 0.0;
  // LiPaC's feedback of the previous frame, read before this frame's update: the counts the
  // trace made (each weighted by --feedback-stride, its own tally) and the sum its counters
  // hold; they differ only when an invocation's buffered counts were dropped or written
  // twice. Not in the CSV.
  std::uint64_t feedbackCounts = 0;
  std::uint64_t feedbackCountsArrived = 0;
  // The wavefront path tracer (--shading wavefront): GPU time of each kind of pass, summed
  // over the frame's rounds and bounces (timestamps after every pass; 0 for the megakernel).
  double wavefrontGenerateMilliseconds = 0.0;
  double wavefrontTraceMilliseconds = 0.0;
  double wavefrontShadeMilliseconds = 0.0;
  double wavefrontQueueMilliseconds = 0.0;
  double wavefrontShadowMilliseconds = 0.0;
  double wavefrontFinishMilliseconds = 0.0;
  // With material graphs: the three binning passes, and every bin's material pass.
  double wavefrontBinMilliseconds = 0.0;
  double wavefrontMaterialMilliseconds = 0.0;
  // With the texel cache: the lookup pass (a hit's values read, a miss binned for its
  // material pass, which inserts it).
  double wavefrontLookupMilliseconds = 0.0;
  // With materials that read a traced input (Ambient Occlusion, Bevel): the traced-inputs
  // pass, which traces their rays from those materials' hits.
  double wavefrontTracedInputsMilliseconds = 0.0;
  // Hits each material bin (distinct graph, in LinkedMaterials::distinct order) evaluated
  // over the frame's rounds and bounces. Not in the CSV.
  std::vector<std::uint32_t> wavefrontBinHits;
  double cacheHitRate() const { return cacheLookups ? double(cacheHits) / cacheLookups : 0.0; }
};

// The ray-tracing pipeline's stack (VK_KHR_ray_tracing_pipeline, "Ray Tracing Pipeline
// Stack"), bytes per invocation: the drivers' figures per shader and what the pipeline is set
// to. All 0 on the query backend.
struct RayTracingStack {
  std::uint32_t raygen = 0;  // the larger of the path tracer and the fill pass
  std::uint32_t closestHit = 0;
  std::uint32_t miss = 0;           // the larger of the two misses
  std::uint32_t callableMax = 0;    // the largest material callable
  std::uint32_t driverDefault = 0;  // the spec's default: raygen + max(hit, miss) + 2 x callable
  std::uint32_t pipeline = 0;       // what is set: raygen + max(hit, miss, callable)
};

struct RenderStats {
  std::string device;
  std::string backend;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t pathsPerPixel = 0;
  std::uint32_t raysPerPath = 0;
  std::vector<FrameStats> frames;
  AccelerationStructureStats accelerationStructures;
  std::uint64_t textureBytes = 0;
  std::uint32_t materialCount = 0;
  double materialCompileMilliseconds = 0.0;  // graph → GLSL
  double shaderCompileMilliseconds = 0.0;    // GLSL → SPIR-V (0 when all came from the cache)
  std::uint32_t shaderCacheHits = 0;
  std::uint32_t shadersCompiled = 0;
  // "switch", "callable", "floor" (no graph evaluated) or "ao" (--integrator ao: none either)
  std::string materialDispatch;
  // --integrator ao: the AO rays from each primary hit and their length (the scene's default
  // resolved); 0 for the path tracer.
  std::uint32_t ambientOcclusionSamples = 0;
  float ambientOcclusionDistance = 0.0f;
  std::string shading = "megakernel";  // "megakernel" or "wavefront" (--shading)
  // The wavefront's paths in flight (its path state's slots, --wavefront-paths) and the
  // chunks a round of the image ran in (1 when every pixel has a slot); 0 for the megakernel.
  std::uint32_t wavefrontPathSlots = 0;
  std::uint32_t wavefrontChunks = 0;
  // The wavefront's material passes (one a distinct graph; 0 for the megakernel or the
  // floor) as a driver that inlines every call compiles them (vk/spirv_size.h), summed over
  // the passes: their instructions, and their graphs' (EvaluateMaterial_<name>, one copy
  // each); and the most copies of its graph one pass holds.
  std::uint32_t wavefrontMaterialPasses = 0;
  std::uint64_t wavefrontMaterialInlinedInstructions = 0;
  std::uint64_t wavefrontMaterialGraphInstructions = 0;
  std::uint64_t wavefrontMaterialGraphCopiesMax = 0;
  // Shader modules and pipeline (the driver's own compile), excluding GLSL → SPIR-V.
  double pipelineCreateMilliseconds = 0.0;
  // The pipelines created for the render (the animated meshes' pass included) and, where
  // the driver says (VK_EXT_pipeline_creation_feedback: pipelineCacheHitsReported), how many
  // it found in the pipeline cache. The driver's data read from the cache file when the
  // device was opened (0: none, or the file was ignored), and whether the render wrote the
  // file back (false when nothing was new).
  std::uint32_t pipelinesCreated = 0;
  std::uint32_t pipelineCacheHits = 0;
  bool pipelineCacheHitsReported = false;
  std::uint64_t pipelineCacheLoadedBytes = 0;
  bool pipelineCacheWritten = false;
  // The pipelines' creation calls' wall times summed: against pipelineCreateMilliseconds it
  // says how many the driver compiled at a time (threads that wait on a lock in the driver
  // add time here without shortening the wall time).
  double pipelineCreateCallMilliseconds = 0.0;
  // Pipelines created between the first frame and the second (FrameTracer::
  // createDeferredPipelines: the wavefront's graphs' own material passes), and the wall time
  // that took, GLSL compiles included; where the driver says, how many came from the cache.
  std::uint32_t deferredPipelinesCreated = 0;
  std::uint32_t deferredPipelineCacheHits = 0;
  double deferredPipelineMilliseconds = 0.0;
  // Wall time from the start of Renderer::render (the device is open by then) to the end of
  // the first frame read back: every set-up stage (materials, upload, acceleration
  // structures, shaders, pipelines) and the first frame.
  double firstFrameMilliseconds = 0.0;
  RayTracingStack rayTracingStack;  // pipeline backend only
  std::string cache = "none";       // "none", "texel" or "tile"
  std::string cacheTile;            // tile cache: "4x4 nearest entry [grouped]"
  std::string cacheEviction;        // "none" or "lru" (empty without a cache)
  std::uint32_t cacheEntries = 0;
  // The default entry count was halved to fit the device's storage-buffer range.
  bool cacheEntriesFitted = false;
  std::uint32_t cacheProbe = 0;
  std::string cacheReadCheck;         // "key" or "counter" (§5.3.4)
  std::uint32_t cacheValueCount = 0;  // floats per entry
  std::string cacheValueFormat;       // "fp32" or "fp16" (§5.3.1)
  std::string cacheClock;             // "frame" or "counter" (§5.3.3)
  bool cacheSnapUv = false;           // misses evaluated at the texel centre (§6.1)
  bool cacheSecondaryOnly = false;    // primary hits bypass the cache (Fig. 6.6)
  // The texel cache's --cache-filter: "nearest", "trilinear" or "stochastic".
  std::string cacheFilter = "nearest";
  std::string cacheKeyDomains = "all";  // --cache-keys
  std::string cacheRefresh;             // cacheRefreshText of the texel cache's refresh
  std::uint64_t cacheBytes = 0;
  std::string culling = "none";  // --culling: none, frustum or lipac
  // The share of the scene's estimated material cost (compiler/cut.h's per-node estimates,
  // uncalibrated) that this render's cache can serve: every instance weighs by its graph's
  // estimated cost; a whole cacheable (uv-only) graph counts whole, a cut its cutCostShare where
  // this render keys cuts (the texel cache of the switch megakernel or the wavefront), by key
  // domain. Times the hit rate, it estimates the share of material cost served from the
  // cache. All 0 without a cache.
  struct CachedCostShare {
    double whole = 0.0, uv = 0.0, object = 0.0, world = 0.0;
    double total() const { return whole + uv + object + world; }
  } cachedCostShare;

  double medianGpuMilliseconds() const;
  std::uint64_t totalRays() const;
  // "1048576 entries", saying when the default count was fitted to the device (what
  // `render` and `bench` print).
  std::string cacheEntriesText() const;
};

// "12 pipelines, 12 from the pipeline cache" (or "..., the driver does not say how many from
// the pipeline cache"): what `render` and `bench` print after the pipeline time.
std::string pipelineCacheText(const RenderStats& stats);

// One header line, then one line per frame; set-up figures repeat on every line so each
// line stands alone in a spreadsheet.
void writeStatsCsv(std::ostream& out, const RenderStats& stats);

}  // namespace memograph::runtime
