// memograph bench [SCENES...] [--size WxH ...]: frames and rays per second of the path
// tracer on the built-in scenes, from GPU timestamps, as medians over timed frames after
// warm-up frames (thesis §6 settings: 1920x1080, P = 6, L = 4).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <span>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "runtime/host/atomic_file.h"

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "bench_frames.h"
#include "bench_summary.h"
#include "option_table.h"
#include "runtime/renderer.h"
#include "runtime/scene/pack/scene_pack.h"
#include "scene_inputs.h"
#endif
#ifdef MEMOGRAPH_HAVE_SCENES
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#include "runtime/scene/scene_limits.h"
#include "runtime/trace/render_setup.h"
#endif

namespace memograph::cli {

#if !defined(MEMOGRAPH_HAVE_RUNTIME) || !defined(MEMOGRAPH_HAVE_SCENES)
int runBench(std::span<const std::string_view>) {
  std::cerr << "memograph bench: this build lacks the renderer or the built-in scenes\n";
  return kExitFailure;
}
#else

namespace {

constexpr std::string_view kIntro =
    "usage: memograph bench [builtin:NAME[:KEY=VALUE,...]|FILE.mgpack ...] [options]\n"
    "\n"
    "Renders each scene at each size and prints the median GPU frame time, frames per\n"
    "second and rays per second over the timed frames (after warm-up frames). The camera\n"
    "follows the scene's built-in camera path unless --static-camera is given; a scene pack\n"
    "('memograph pack') follows its own path, spread over the path's cameras, or stays at\n"
    "its camera when it has none. Scenes default to builtin:classroom builtin:landscape;\n"
    "options as in 'render', e.g. builtin:classroom:octaves=10,layers=3. On a GPU the\n"
    "device first runs a spinning compute pass for 0.5 s (again after the pipelines made\n"
    "before the second frame), so that the timed frames start with its clocks raised.\n";

// RenderSettings::clockWarmupMilliseconds: what the introduction above says.
constexpr std::uint32_t kClockWarmupMilliseconds = 500;

using Clock = std::chrono::steady_clock;

// One bench command: its options, its frame plan and what it writes at the end.
struct Bench {
  TraceCommandOptions options;
  BenchFramePlan plan;
  Clock::time_point start;  // --time-limit counts from here
  std::ostringstream csv;
  std::ostringstream pipelineStatistics;  // --pipeline-statistics: every scene's rows
  std::vector<std::pair<std::string, std::string> > outputs;  // written as a set at the end
  std::optional<runtime::Scene> firstScene;  // built by the checks, taken by its run
};

// The frame plan and every scene, checked before anything is rendered or written: each
// scene is built here (its name and ranges are checked by building it), so that a bad second
// scene is not found after the first one
// has been measured. The first scene is kept for its run; the others are built again then,
// one at a time, so that a sweep's scenes are never all in memory at once.
int checkPlanAndScenes(Bench& bench, const std::vector<std::string>& scenes) {
  const TraceCommandOptions& o = bench.options;
  bench.plan = {.warmup = o.warmup,
                .timed = o.settings.frames,
                .stride = o.frameStride,
                .pathCameras = o.cameraFrames.value_or(o.settings.frames * o.frameStride)};
  if (o.staticCamera && (o.frameStride != 1 || o.cameraFrames))
    return usageError(
        "bench", "--frame-stride and --camera-frames need the camera path, not --static-camera");
  for (const auto& sceneName : scenes) {
    if (runtime::isScenePackPath(sceneName))
      continue;
    if (sceneName.rfind("builtin:", 0) != 0)
      return usageError("bench",
                        "bench runs built-in scenes (builtin:NAME) and scene packs "
                        "(.mgpack), not '" +
                            sceneName + "'");
    std::string error;
    if (!runtime::parseBuiltinSceneSpec(std::string_view(sceneName).substr(8), error))
      return usageError("bench", error);
  }
  const auto geometryCheck = runtime::deviceGeometryCheck(o.renderer.context);
  for (const auto& sceneName : scenes) {
    std::string error;
    if (runtime::isScenePackPath(sceneName)) {
      // Read here to be checked (a bad pack is found before any scene is measured).
      if (!runtime::readScenePack(sceneName, error)) {
        std::cerr << "memograph bench: " << error << "\n";
        return kExitFailure;
      }
      continue;
    }
    auto spec = runtime::parseBuiltinSceneSpec(std::string_view(sceneName).substr(8), error);
    spec->options.onGeometry = geometryCheck;
    spec->options.meshLods = o.renderer.culling.showsMeshLods();
    runtime::Scene scene;
    try {
      scene = runtime::makeBuiltinScene(spec->name, spec->options);
    } catch (const std::invalid_argument& e) {
      return usageError("bench", e.what());
    } catch (const runtime::SceneLimitError& e) {
      // Too large for the device: refused while the scene is built (exit 1).
      std::cerr << "memograph bench: " << sceneName << ": " << e.what() << "\n";
      return kExitFailure;
    }
    if (!bench.firstScene)
      bench.firstScene = std::move(scene);
  }
  return kExitOk;
}

// The checks across options and the notes for unused ones.
int checkModes(TraceCommandOptions& options) {
  try {
    validateTraceOptions(options);
  } catch (const std::invalid_argument& e) {
    return usageError("bench", e.what());
  }
  for (const std::string& line : ignoredOptionNotes(options))
    std::cerr << "memograph bench: " << line << "\n";
  // A cache carries state from frame to frame, so skipping frames would measure another
  // run, not a sample of this one.
  if (options.frameStride != 1 && options.renderer.cache.mode != runtime::CacheMode::None)
    return usageError("bench",
                      "--frame-stride needs --cache none: with a cache each frame "
                      "depends on the frames before it, so every frame must be rendered");
  return kExitOk;
}

void writeCsvHeader(std::ostream& csv) {
  csv << "scene,width,height,paths,rays_per_path,backend,device,frames,median_gpu_ms,fps,"
         "mrays_per_s,blas_bytes,tlas_bytes,scratch_bytes,materials,material_dispatch,"
         "shader_compile_ms,pipeline_create_ms,cache,cache_eviction,cache_entries,"
         "cache_probe,cache_bytes,median_cache_hit_rate,label,warmup,frame_stride,camera_frames,"
      << benchSummaryCsvColumns()
      << ",cache_value_format,cache_clock,cache_snap_uv,cache_secondary_only,cache_tile,"
         "culling,shading,"
      << wavefrontPassCsvColumns() << ",frames_requested,stopped_early\n";
}

// A scene's names in the output: `csv`, the whole spec, so runs with different options
// stay apart (commas become ';' to keep the CSV's columns); `file`, for the per-frame
// file; `shown`, with --label's name of the variant.
struct RunNames {
  std::string csv, file, shown;
};

RunNames runNames(const std::string& sceneName, const std::string& runLabel) {
  RunNames names;
  names.csv = runtime::isScenePackPath(sceneName) ? std::filesystem::path(sceneName).stem().string()
                                                  : sceneName.substr(8);
  std::replace(names.csv.begin(), names.csv.end(), ',', ';');
  names.file = names.csv;
  std::replace_if(
      names.file.begin(), names.file.end(), [](char c) { return c == ':' || c == ';'; }, '_');
  names.shown = runLabel.empty() ? names.csv : names.csv + " [" + runLabel + "]";
  if (!runLabel.empty())
    names.file += "_" + runLabel;
  return names;
}

// The per-frame file of a scene's run at one size (--frames-csv PREFIX).
std::string framesCsvPath(const TraceCommandOptions& options, const RunNames& names,
                          ImageSize size) {
  return options.framesCsv + names.file + "_" + std::to_string(size.width) + "x" +
         std::to_string(size.height) + ".csv";
}

// Outputs are checked before any work, and written whole at the end (files::): an
// existing --csv is not truncated by a run that then fails. The usage errors (an output
// over an input or another output, --device) come before the folders' checks.
int checkOutputs(const TraceCommandOptions& options, const std::vector<std::string>& scenes) {
  std::vector<CommandFile> outputs = {{"--csv", options.csv},
                                      {"--pipeline-statistics", options.pipelineStatistics}};
  if (!options.framesCsv.empty()) {
    for (const std::string& sceneName : scenes) {
      const RunNames names = runNames(sceneName, options.label);
      for (const ImageSize size : options.sizes)
        outputs.push_back({"--frames-csv file", framesCsvPath(options, names, size)});
    }
  }
  std::vector<CommandFile> inputs;
  addFolderInputs(inputs, "--nodes file", options.renderer.nodeLibraryDirectory, ".inc", true);
  if (const int code = refuseOutputOverInput("bench", outputs, inputs); code != kExitOk)
    return code;
  if (const int code = checkDeviceIndex("bench", options.renderer.context.deviceIndex);
      code != kExitOk)
    return code;
  for (const std::string& file : {options.csv, options.pipelineStatistics}) {
    if (file.empty())
      continue;
    if (const int code = checkOutputFile("bench", file); code != kExitOk)
      return code;
  }
  if (!options.framesCsv.empty()) {
    // PREFIX names a folder and the start of file names: that folder must exist.
    std::string error;
    if (!files::checkOutputPath(options.framesCsv + "frames.csv", error)) {
      std::cerr << "memograph bench: --frames-csv " << options.framesCsv << ": " << error << "\n";
      return kExitFailure;
    }
  }
  return kExitOk;
}

// The device and the memory limits a cache size runs into (recorded with the figures).
void printDevice(const runtime::Renderer& renderer) {
  const auto& device = renderer.context().info();
  std::cout << "device: " << device.name << ", backend "
            << runtime::backendName(renderer.context().backend()) << " (largest allocation "
            << (device.maxMemoryAllocationSize >> 20) << " MiB, storage-buffer range "
            << (device.limits.maxStorageBufferRange >> 20) << " MiB)\n";
  // Flushed line by line: a sweep reads this log through a pipe, and a step that dies
  // (a timeout, a crash in the driver) must still show how far it got.
  std::cout.flush();
}

// One run's figures: one render of a scene at one size.
struct BenchRun {
  const runtime::RenderResult& result;
  std::span<const runtime::FrameStats> timed;
  TimedFrameSummary summary;
  std::uint32_t width, height;
  bool stoppedEarly;
  double fps() const {
    return summary.medianMilliseconds > 0 ? 1000.0 / summary.medianMilliseconds : 0.0;
  }
};

// The cached share of the estimated material cost and, times the hit rate, the share served
// from the cache (RenderStats::cachedCostShare).
std::string cachedShareText(const runtime::RenderStats::CachedCostShare& share, double hitRate) {
  std::ostringstream text;
  text << "cached share " << 100.0 * share.total() << " % of the estimated material cost (whole "
       << 100.0 * share.whole << " %, cuts uv " << 100.0 * share.uv << " %, object "
       << 100.0 * share.object << " %, world " << 100.0 * share.world
       << " %; each instance weighted by its graph's estimated cost); served from the cache "
       << 100.0 * share.total() * hitRate << " %";
  return text.str();
}

void printCacheAndCulling(const BenchRun& run) {
  const runtime::RenderStats& stats = run.result.stats;
  if (stats.cache != "none")
    std::cout << "  cache " << stats.cache << " (" << stats.cacheEntriesText()
              << ", D=" << stats.cacheProbe << ", eviction " << stats.cacheEviction << ", clock "
              << stats.cacheClock << ", " << stats.cacheValueFormat << ", " << stats.cacheBytes
              << " B" << (stats.cacheTile.empty() ? "" : ", tiles " + stats.cacheTile)
              << (stats.cacheSnapUv ? ", snapped uv" : "")
              << (stats.cacheFilter != "nearest" ? ", filter " + stats.cacheFilter : "")
              << (stats.cacheKeyDomains != "all" ? ", keys " + stats.cacheKeyDomains : "")
              << (stats.cacheRefresh.empty() ? "" : ", " + stats.cacheRefresh)
              << (stats.cacheSecondaryOnly ? ", secondary hits only" : "") << "): median hit rate "
              << 100.0 * run.summary.medianCacheHitRate << " %, total "
              << 100.0 * run.summary.totalCacheHitRate << " %\n"
              << "  " << cachedShareText(stats.cachedCostShare, run.summary.totalCacheHitRate)
              << "\n";
  if (stats.culling != "none" && !run.timed.empty()) {
    std::uint64_t peakBytes = 0, builds = 0, evictions = 0;
    for (const auto& frame : run.timed) {
      peakBytes = std::max(peakBytes, frame.blasBytes + frame.tlasBytes);
      builds += frame.blasBuilds;
      evictions += frame.blasEvictions;
    }
    const auto& last = run.timed.back();
    std::cout << "  culling " << stats.culling << ": last frame " << last.activeInstances
              << " active, " << last.omittedInstances << " omitted, " << last.inactiveInstances
              << " inactive instances";
    if (last.hitboxes)
      std::cout << ", " << last.activeHitboxes << " of " << last.hitboxes << " hitboxes active";
    std::cout << "; peak AS " << peakBytes << " B; " << builds << " BLAS builds, " << evictions
              << " evictions over the timed frames\n";
  }
}

void printRun(const Bench& bench, const RunNames& names, const BenchRun& run) {
  const TraceCommandOptions& o = bench.options;
  const runtime::RenderStats& stats = run.result.stats;
  const auto& as = stats.accelerationStructures;
  std::cout << names.shown << " " << run.width << "x" << run.height
            << " P=" << o.settings.pathsPerPixel << " L=" << o.settings.raysPerPath << ": median "
            << run.summary.medianMilliseconds << " ms/frame, " << run.fps() << " fps, "
            << run.summary.medianMraysPerSecond << " Mrays/s (" << run.timed.size() << " frames";
  if (!o.staticCamera)
    std::cout << " of a " << bench.plan.pathCameras << "-camera path, stride " << bench.plan.stride;
  std::cout << "; " << stats.materialCount << " materials, " << stats.materialDispatch << ", "
            << stats.shading << "; pipeline " << stats.pipelineCreateMilliseconds << " ms ("
            << runtime::pipelineCacheText(stats) << "); BLAS " << as.blasBytes << " B, TLAS "
            << as.tlasBytes << " B)\n";
  if (stats.ambientOcclusionSamples > 0)
    std::cout << "  ambient occlusion (seeds/004 §3): " << stats.ambientOcclusionSamples
              << " rays of length " << stats.ambientOcclusionDistance
              << " from each path's primary hit; Mrays/s counts them and the primary rays\n";
  if (const auto& stack = stats.rayTracingStack; stack.driverDefault > 0)
    std::cout << "  ray-tracing stack " << stack.pipeline << " B an invocation (the spec's "
              << "default " << stack.driverDefault << " B; raygen " << stack.raygen << ", hit "
              << stack.closestHit << ", miss " << stack.miss << ", largest callable "
              << stack.callableMax << ")\n";
  if (stats.shading == "wavefront")
    std::cout << "  wavefront passes, median GPU ms a frame: trace "
              << run.summary.medianWavefrontTraceMilliseconds << ", shade "
              << run.summary.medianWavefrontShadeMilliseconds << ", shadow "
              << run.summary.medianWavefrontShadowMilliseconds << ", queue "
              << run.summary.medianWavefrontQueueMilliseconds << ", bin "
              << run.summary.medianWavefrontBinMilliseconds << ", material "
              << run.summary.medianWavefrontMaterialMilliseconds << ", lookup "
              << run.summary.medianWavefrontLookupMilliseconds << ", traced inputs "
              << run.summary.medianWavefrontTracedInputsMilliseconds << "; "
              << stats.wavefrontPathSlots << " paths in flight, " << stats.wavefrontChunks
              << " chunk(s) a round\n";
  if (run.stoppedEarly)
    std::cout << "  stopped by --time-limit " << *o.timeLimitSeconds << " s after "
              << stats.frames.size() << " of " << o.warmup + o.settings.frames << " frames ("
              << run.timed.size() << " of " << o.settings.frames
              << " timed): the figures cover those only\n";
  printCacheAndCulling(run);
  std::cout.flush();
}

void appendCsvRow(Bench& bench, const RunNames& names, const BenchRun& run) {
  const TraceCommandOptions& o = bench.options;
  const runtime::RenderStats& stats = run.result.stats;
  const auto& as = stats.accelerationStructures;
  bench.csv << names.csv << ',' << run.width << ',' << run.height << ',' << o.settings.pathsPerPixel
            << ',' << o.settings.raysPerPath << ',' << stats.backend << ",\"" << stats.device
            << "\"," << run.timed.size() << ',' << run.summary.medianMilliseconds << ','
            << run.fps() << ',' << run.summary.medianMraysPerSecond << ',' << as.blasBytes << ','
            << as.tlasBytes << ',' << as.scratchBytes << ',' << stats.materialCount << ','
            << stats.materialDispatch << ',' << stats.shaderCompileMilliseconds << ','
            << stats.pipelineCreateMilliseconds << ',' << stats.cache << ',' << stats.cacheEviction
            << ',' << stats.cacheEntries << ',' << stats.cacheProbe << ',' << stats.cacheBytes
            << ',' << run.summary.medianCacheHitRate << ',' << o.label << ',' << o.warmup << ','
            << (o.staticCamera ? 0 : bench.plan.stride) << ','
            << (o.staticCamera ? 0 : bench.plan.pathCameras) << ','
            << benchSummaryCsvValues(run.summary) << ',' << stats.cacheValueFormat << ','
            << stats.cacheClock << ',' << int(stats.cacheSnapUv) << ','
            << int(stats.cacheSecondaryOnly) << ',' << stats.cacheTile << ',' << stats.culling
            << ',' << stats.shading << ',' << wavefrontPassCsvValues(run.summary, stats) << ','
            << o.settings.frames << ',' << int(run.stoppedEarly) << '\n';
}

// Renders `scene` at one size and reports it: printed, a CSV line, a per-frame file.
void benchSize(Bench& bench, runtime::Renderer& renderer, const runtime::Scene& scene,
               const RunNames& names, ImageSize size, const std::vector<runtime::Camera>& cameras) {
  const TraceCommandOptions& o = bench.options;
  runtime::RenderSettings settings = o.settings;
  settings.width = size.width;
  settings.height = size.height;
  settings.frames = o.warmup + o.settings.frames;
  settings.cameraPath = cameras;
  settings.clockWarmupMilliseconds = kClockWarmupMilliseconds;
  if (o.timeLimitSeconds)
    settings.continueAfterFrame = [start = bench.start,
                                   limit = *o.timeLimitSeconds](const runtime::FrameStats&) {
      return std::chrono::duration<double>(Clock::now() - start).count() < limit;
    };
  const runtime::RenderResult result = renderer.render(scene, settings);
  const auto timed = std::span(result.stats.frames)
                         .subspan(std::min<std::size_t>(o.warmup, result.stats.frames.size()));
  const BenchRun run{result,     timed,       summarizeTimedFrames(timed),
                     size.width, size.height, result.stats.frames.size() < settings.frames};
  printRun(bench, names, run);
  if (!o.csv.empty())
    appendCsvRow(bench, names, run);
  if (!o.framesCsv.empty()) {
    std::ostringstream perFrame;
    runtime::writeStatsCsv(perFrame, result.stats);
    bench.outputs.emplace_back(framesCsvPath(o, names, size), perFrame.str());
  }
}

// --pipeline-statistics: the statistics of the pipelines a scene's renderer created.
void appendPipelineStatistics(Bench& bench, const runtime::Renderer& renderer,
                              const RunNames& names) {
  if (const runtime::PipelineStatistics* statistics = renderer.context().pipelineStatistics())
    runtime::appendPipelineStatisticsCsv(bench.pipelineStatistics, names.csv, statistics->rows());
}

// The cameras of a pack's own path for each rendered frame: the path's cameras spread over
// the bench's camera positions (bench.plan.pathCameras), so that the timed frames cover the
// whole path whatever its length; none (its own camera) when the pack has no path.
std::vector<runtime::Camera> packCameras(const Bench& bench,
                                         const std::vector<runtime::Camera>& path) {
  const TraceCommandOptions& o = bench.options;
  std::vector<runtime::Camera> cameras;
  if (o.staticCamera || path.empty())
    return cameras;
  for (std::uint32_t frame = 0; frame < o.warmup + o.settings.frames; ++frame) {
    const std::uint64_t index = benchCameraIndex(bench.plan, frame);
    cameras.push_back(path[index * path.size() / bench.plan.pathCameras]);
  }
  return cameras;
}

// Renders a scene pack at every size (read once already by checkPlanAndScenes).
void benchPack(Bench& bench, const std::string& sceneName) {
  TraceCommandOptions o = bench.options;  // its own texture loader
  runtime::Scene scene;
  std::vector<runtime::Camera> path;
  if (loadScenePackFile("bench", sceneName, o, scene, path) != kExitOk)
    throw std::runtime_error("scene pack " + sceneName + " could not be read again");
  if (o.noEmissiveNee)
    scene.emissiveLightSampling = false;
  o.renderer.context.autoPrefersPipeline =
      runtime::countDistinctMaterialGraphs(scene) > runtime::kManyMaterialGraphs;
  runtime::Renderer renderer(o.renderer);
  printDevice(renderer);
  const RunNames names = runNames(sceneName, o.label);
  for (const ImageSize size : o.sizes)
    benchSize(bench, renderer, scene, names, size, packCameras(bench, path));
  appendPipelineStatistics(bench, renderer, names);
}

// Renders one scene at every size (checked by checkPlanAndScenes).
void benchScene(Bench& bench, const std::string& sceneName) {
  TraceCommandOptions& o = bench.options;
  if (runtime::isScenePackPath(sceneName))
    return benchPack(bench, sceneName);
  std::string error;
  const auto spec = runtime::parseBuiltinSceneSpec(std::string_view(sceneName).substr(8), error);
  runtime::Scene scene;
  if (bench.firstScene) {
    scene = std::move(*bench.firstScene);
    bench.firstScene.reset();
  } else {
    runtime::BuiltinSceneOptions sceneOptions = spec->options;
    sceneOptions.meshLods = o.renderer.culling.showsMeshLods();
    scene = runtime::makeBuiltinScene(spec->name, sceneOptions);  // checked already
  }
  if (o.noEmissiveNee)
    scene.emissiveLightSampling = false;
  // Each scene gets its own renderer: --backend auto depends on its material count.
  o.renderer.context.autoPrefersPipeline =
      runtime::countDistinctMaterialGraphs(scene) > runtime::kManyMaterialGraphs;
  runtime::Renderer renderer(o.renderer);
  printDevice(renderer);
  std::vector<runtime::Camera> cameras;
  if (!o.staticCamera) {
    const auto path =
        runtime::makeBuiltinCameraPath(spec->name, int(bench.plan.pathCameras),
                                       spec->options.cityScale, spec->options.cityPath)
            .frames;
    for (std::uint32_t frame = 0; frame < o.warmup + o.settings.frames; ++frame)
      cameras.push_back(path[benchCameraIndex(bench.plan, frame)]);
  }
  const RunNames names = runNames(sceneName, o.label);
  for (const ImageSize size : o.sizes)
    benchSize(bench, renderer, scene, names, size, cameras);
  appendPipelineStatistics(bench, renderer, names);
}

}  // namespace

int runBench(std::span<const std::string_view> args) {
  Bench bench;
  // --time-limit is a deadline for the whole command, so a caller with a hard limit of its
  // own (the memoization sweep's per-step timeout) gets figures back however long set-up took.
  bench.start = Clock::now();
  std::vector<std::string> scenes;
  if (const auto exitCode =
          scanTraceOptions(TraceCommand::Bench, args, kIntro, bench.options, scenes))
    return *exitCode;
  if (scenes.empty())
    scenes = {"builtin:classroom", "builtin:landscape"};
  // Every usage check first (the scenes last, as they are built to be checked), then the
  // outputs' folders.
  if (const int code = checkModes(bench.options); code != kExitOk)
    return code;
  if (const int code = checkPlanAndScenes(bench, scenes); code != kExitOk)
    return code;
  if (const int code = checkOutputs(bench.options, scenes); code != kExitOk)
    return code;
  if (!bench.options.csv.empty())
    writeCsvHeader(bench.csv);
  try {
    for (const auto& sceneName : scenes)
      benchScene(bench, sceneName);
  } catch (const std::invalid_argument& e) {
    // The renderer's refusals of option combinations (e.g. --wavefront-paths when
    // --shading auto chose the megakernel): usage errors, as when the CLI catches them.
    return usageError("bench", e.what());
  } catch (const std::exception& e) {
    std::cerr << "memograph bench: " << e.what() << "\n";
    return kExitFailure;
  }
  if (!bench.options.csv.empty())
    bench.outputs.emplace_back(bench.options.csv, bench.csv.str());
  if (!bench.options.pipelineStatistics.empty())
    bench.outputs.emplace_back(
        bench.options.pipelineStatistics,
        runtime::kPipelineStatisticsCsvHeader + bench.pipelineStatistics.str());
  std::string error;
  if (!writeFilesAtomically(bench.outputs, error)) {
    std::cerr << "memograph bench: " << error << "\n";
    return kExitFailure;
  }
  return kExitOk;
}
#endif

}  // namespace memograph::cli
