// memograph bench [SCENES...] [--size WxH ...]: frames and rays per second of the path
// tracer on the built-in scenes, from GPU timestamps, as medians over timed frames after
// warm-up frames (thesis §6 settings: 1920x1080, P = 6, L = 4).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>
#include <iostream>
#include <span>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "runtime/host/atomic_file.h"

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "bench_frames.h"
#include "bench_summary.h"
#include "renderer_arguments.h"
#include "runtime/renderer.h"
#endif
#ifdef MEMOGRAPH_HAVE_SCENES
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#endif

namespace memograph::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: memograph bench [builtin:NAME[:KEY=VALUE,...] ...] [options]\n"
    "\n"
    "Renders each scene at each size and prints the median GPU frame time, frames per\n"
    "second and rays per second over the timed frames (after warm-up frames). The camera\n"
    "follows the scene's built-in camera path unless --static-camera is given. Scenes\n"
    "default to builtin:classroom builtin:landscape; options as in 'render', e.g.\n"
    "builtin:classroom:octaves=10,layers=3.\n"
    "\n"
    "options:\n"
    "  --sizes LIST          comma-separated WxH sizes (default 1920x1080)\n"
    "  --paths P             paths per pixel (default 6)\n"
    "  --bounces L           rays per path (default 4)\n"
    "  --frames F            timed frames (default 20)\n"
    "  --warmup W            untimed frames first (default 3); they follow the path up to\n"
    "                        its first camera (the path is a closed loop)\n"
    "  --camera-frames N     cameras on the path (default F x K): its length in frames\n"
    "  --frame-stride K      time every K-th camera of the path only (default 1); for runs\n"
    "                        without a cache, whose frames do not depend on earlier ones\n"
    "  --label NAME          names the run (letters, digits, '.', '_', '-') in the output,\n"
    "                        the CSV and the per-frame file name\n"
    "  --time-limit S        stop rendering once the bench has run S seconds (wall time,\n"
    "                        set-up and shader compiles included): the run in progress ends\n"
    "                        after its current frame, later runs after their first; the\n"
    "                        summary covers the timed frames rendered and says it stopped\n"
    "                        early (CSV: stopped_early, frames_requested)\n"
    "  --static-camera       keep the scene's camera still\n"
    "  --csv FILE            one line per scene and size\n"
    "  --frames-csv PREFIX   per-frame statistics to PREFIX<scene>[_<label>]_<W>x<H>.csv\n";

}  // namespace

#if !defined(MEMOGRAPH_HAVE_RUNTIME) || !defined(MEMOGRAPH_HAVE_SCENES)
int runBench(std::span<const std::string_view>) {
  std::cerr << "memograph bench: this build lacks the renderer or the built-in scenes\n";
  return kExitFailure;
}
#else

int runBench(std::span<const std::string_view> args) {
  std::string sizes = "1920x1080", paths = "6", bounces = "4", frames = "20", warmup = "3", csvPath,
              framesCsv, cameraFrames, frameStride = "1", runLabel, timeLimit;
  bool staticCamera = false;
  ArgumentScanner scanner("bench", args);
  RendererArguments rendererArguments;
  rendererArguments.registerWith(scanner);
  scanner.option("--sizes", &sizes);
  scanner.option("--size", &sizes);
  scanner.option("--paths", &paths);
  scanner.option("--bounces", &bounces);
  scanner.option("--frames", &frames);
  scanner.option("--warmup", &warmup);
  scanner.option("--csv", &csvPath);
  scanner.option("--frames-csv", &framesCsv);
  scanner.option("--camera-frames", &cameraFrames);
  scanner.option("--frame-stride", &frameStride);
  scanner.option("--label", &runLabel);
  scanner.option("--time-limit", &timeLimit);
  scanner.flag("--static-camera", &staticCamera);
  scanner.help({kHelp, kRendererHelp, kCacheHelp, kCullingHelp});
  std::vector<std::string> scenes;
  if (const auto exitCode = scanner.scan(scenes))
    return *exitCode;
  if (scenes.empty())
    scenes = {"builtin:classroom", "builtin:landscape"};

  std::uint32_t p = 0, l = 0, f = 0, w = 0;
  if (!parseNumber(paths, p) || !parseNumber(bounces, l) || !parseNumber(frames, f) ||
      !parseNumber(warmup, w) || f == 0 || p == 0 || l == 0)
    return usageError("bench",
                      "--paths, --bounces, --frames (each > 0) and --warmup take whole numbers");
  BenchFramePlan plan{.warmup = w, .timed = f};
  if (!parseNumber(frameStride, plan.stride) || plan.stride == 0)
    return usageError("bench", "--frame-stride takes a whole number > 0");
  plan.pathCameras = f * plan.stride;
  if (!cameraFrames.empty() &&
      (!parseNumber(cameraFrames, plan.pathCameras) || plan.pathCameras == 0))
    return usageError("bench", "--camera-frames takes a whole number > 0");
  if (staticCamera && (plan.stride != 1 || !cameraFrames.empty()))
    return usageError(
        "bench", "--frame-stride and --camera-frames need the camera path, not --static-camera");
  if (!std::all_of(runLabel.begin(), runLabel.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
      }))
    return usageError(
        "bench", "--label takes letters, digits, '.', '_' and '-' only, not '" + runLabel + "'");
  // --time-limit is a deadline for the whole command, so a caller with a hard limit of its
  // own (the memoization sweep's per-step timeout) gets figures back however long set-up took.
  const auto start = std::chrono::steady_clock::now();
  double timeLimitSeconds = -1.0;  // none
  if (!timeLimit.empty() && (!parseReal(timeLimit, timeLimitSeconds) || timeLimitSeconds < 0.0))
    return usageError("bench",
                      "--time-limit takes seconds (a number >= 0), not '" + timeLimit + "'");
  std::vector<std::pair<std::uint32_t, std::uint32_t> > sizeList;
  std::stringstream sizeStream(sizes);
  for (std::string item; std::getline(sizeStream, item, ',');) {
    std::uint32_t width = 0, height = 0;
    std::string error;
    if (!parseImageSize(item, width, height, error))
      return usageError("bench", "--sizes takes WxH[,WxH...]: " + error);
    sizeList.push_back({width, height});
  }
  if (sizeList.empty())
    return usageError("bench", "--sizes needs at least one WxH, e.g. 1920x1080");
  // Every scene name is checked before anything is rendered or written.
  for (const auto& sceneName : scenes) {
    if (sceneName.rfind("builtin:", 0) != 0)
      return usageError("bench",
                        "bench runs built-in scenes (builtin:NAME), not '" + sceneName + "'");
    std::string error;
    if (!runtime::parseBuiltinSceneSpec(std::string_view(sceneName).substr(8), error))
      return usageError("bench", error);
  }
  runtime::RendererOptions options;
  try {
    options = rendererArguments.parse();
  } catch (const std::invalid_argument& e) {
    return usageError("bench", e.what());
  }
  for (const std::string& line : RendererArguments::ignoredOptions(scanner, options))
    std::cerr << "memograph bench: " << line << "\n";
  // A cache carries state from frame to frame, so skipping frames would measure another
  // run, not a sample of this one.
  if (plan.stride != 1 && options.cache.mode != runtime::CacheMode::None)
    return usageError("bench",
                      "--frame-stride needs --cache none: with a cache each frame "
                      "depends on the frames before it, so every frame must be rendered");

  // Outputs are checked before any work, and written whole at the end (files::): an
  // existing --csv is not truncated by a run that then fails.
  if (!csvPath.empty()) {
    if (const int code = checkOutputFile("bench", csvPath); code != kExitOk)
      return code;
  }
  if (!framesCsv.empty()) {
    // PREFIX names a folder and the start of file names: that folder must exist.
    std::string error;
    if (!files::checkOutputPath(framesCsv + "frames.csv", error)) {
      std::cerr << "memograph bench: --frames-csv " << framesCsv << ": " << error << "\n";
      return kExitFailure;
    }
  }
  std::ostringstream csv;
  std::vector<std::pair<std::string, std::string> > outputs;
  if (!csvPath.empty()) {
    csv << "scene,width,height,paths,rays_per_path,backend,device,frames,median_gpu_ms,fps,"
           "mrays_per_s,blas_bytes,tlas_bytes,scratch_bytes,materials,material_dispatch,"
           "shader_compile_ms,pipeline_create_ms,cache,cache_eviction,cache_entries,"
           "cache_probe,cache_bytes,median_cache_hit_rate,label,warmup,frame_stride,camera_frames,"
        << benchSummaryCsvColumns()
        << ",cache_value_format,cache_clock,cache_snap_uv,cache_secondary_only,cache_tile,"
           "culling,shading,"
        << wavefrontPassCsvColumns() << ",frames_requested,stopped_early\n";
  }
  try {
    for (const auto& sceneName : scenes) {
      std::string error;
      auto spec = runtime::parseBuiltinSceneSpec(std::string_view(sceneName).substr(8), error);
      const std::string& name = spec->name;
      runtime::Scene scene = runtime::makeBuiltinScene(name, spec->options);
      if (options.shading == runtime::Shading::Wavefront && !scene.animatedMeshes.empty())
        return usageError("bench", "--shading wavefront renders static scenes only; " + sceneName +
                                       " has animated meshes");
      if (rendererArguments.noEmissiveNee)
        scene.emissiveLightSampling = false;
      // Each scene gets its own renderer: --backend auto depends on its material count.
      options.context.autoPrefersPipeline =
          runtime::countDistinctMaterialGraphs(scene) > runtime::kManyMaterialGraphs;
      runtime::Renderer renderer(options);
      // The memory limits a cache size runs into (recorded with the figures).
      const auto& device = renderer.context().info();
      std::cout << "device: " << device.name << ", backend "
                << runtime::backendName(renderer.context().backend()) << " (largest allocation "
                << (device.maxMemoryAllocationSize >> 20) << " MiB, storage-buffer range "
                << (device.limits.maxStorageBufferRange >> 20) << " MiB)\n";
      // Flushed line by line: a sweep reads this log through a pipe, and a step that dies
      // (a timeout, a crash in the driver) must still show how far it got.
      std::cout.flush();
      // Output label: the whole spec, so runs with different options stay apart; commas
      // become ';' to keep the CSV's columns. --label adds the variant's name.
      std::string label = sceneName.substr(8);
      std::replace(label.begin(), label.end(), ',', ';');
      std::string fileLabel = label;
      std::replace_if(
          fileLabel.begin(), fileLabel.end(), [](char c) { return c == ':' || c == ';'; }, '_');
      const std::string shownLabel = runLabel.empty() ? label : label + " [" + runLabel + "]";
      if (!runLabel.empty())
        fileLabel += "_" + runLabel;
      std::vector<runtime::Camera> cameras;
      if (!staticCamera) {
        const auto path =
            runtime::makeBuiltinCameraPath(name, int(plan.pathCameras), spec->options.cityScale,
                                           spec->options.cityPath)
                .frames;
        for (std::uint32_t frame = 0; frame < w + f; ++frame)
          cameras.push_back(path[benchCameraIndex(plan, frame)]);
      }
      for (auto [width, height] : sizeList) {
        runtime::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.pathsPerPixel = p;
        settings.raysPerPath = l;
        settings.frames = w + f;
        settings.sharedPrimaryRay = rendererArguments.sharedPrimary;
        settings.cameraPath = cameras;
        if (timeLimitSeconds >= 0.0)
          settings.continueAfterFrame = [start, timeLimitSeconds](const runtime::FrameStats&) {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
                   timeLimitSeconds;
          };
        runtime::RenderResult result = renderer.render(scene, settings);
        const bool stoppedEarly = result.stats.frames.size() < settings.frames;
        const auto timed = std::span(result.stats.frames)
                               .subspan(std::min<std::size_t>(w, result.stats.frames.size()));
        const TimedFrameSummary summary = summarizeTimedFrames(timed);
        const double medianMs = summary.medianMilliseconds;
        const double fps = medianMs > 0 ? 1000.0 / medianMs : 0.0;
        const auto& as = result.stats.accelerationStructures;
        std::cout << shownLabel << " " << width << "x" << height << " P=" << p << " L=" << l
                  << ": median " << medianMs << " ms/frame, " << fps << " fps, "
                  << summary.medianMraysPerSecond << " Mrays/s (" << timed.size() << " frames";
        if (!staticCamera)
          std::cout << " of a " << plan.pathCameras << "-camera path, stride " << plan.stride;
        std::cout << "; " << result.stats.materialCount << " materials, "
                  << result.stats.materialDispatch << ", " << result.stats.shading << "; pipeline "
                  << result.stats.pipelineCreateMilliseconds << " ms; BLAS " << as.blasBytes
                  << " B, TLAS " << as.tlasBytes << " B)\n";
        if (const auto& stack = result.stats.rayTracingStack; stack.driverDefault > 0)
          std::cout << "  ray-tracing stack " << stack.pipeline << " B an invocation (the spec's "
                    << "default " << stack.driverDefault << " B; raygen " << stack.raygen
                    << ", hit " << stack.closestHit << ", miss " << stack.miss
                    << ", largest callable " << stack.callableMax << ")\n";
        if (result.stats.shading == "wavefront")
          std::cout << "  wavefront passes, median GPU ms a frame: trace "
                    << summary.medianWavefrontTraceMilliseconds << ", shade "
                    << summary.medianWavefrontShadeMilliseconds << ", shadow "
                    << summary.medianWavefrontShadowMilliseconds << ", queue "
                    << summary.medianWavefrontQueueMilliseconds << ", bin "
                    << summary.medianWavefrontBinMilliseconds << ", material "
                    << summary.medianWavefrontMaterialMilliseconds << ", lookup "
                    << summary.medianWavefrontLookupMilliseconds << "; "
                    << result.stats.wavefrontPathSlots << " paths in flight, "
                    << result.stats.wavefrontChunks << " chunk(s) a round\n";
        if (stoppedEarly)
          std::cout << "  stopped by --time-limit " << timeLimit << " s after "
                    << result.stats.frames.size() << " of " << settings.frames << " frames ("
                    << timed.size() << " of " << f << " timed): the figures cover those only\n";
        if (result.stats.cache != "none")
          std::cout << "  cache " << result.stats.cache << " (" << result.stats.cacheEntriesText()
                    << ", D=" << result.stats.cacheProbe << ", eviction "
                    << result.stats.cacheEviction << ", clock " << result.stats.cacheClock << ", "
                    << result.stats.cacheValueFormat << ", " << result.stats.cacheBytes << " B"
                    << (result.stats.cacheTile.empty() ? "" : ", tiles " + result.stats.cacheTile)
                    << (result.stats.cacheSnapUv ? ", snapped uv" : "")
                    << (result.stats.cacheSecondaryOnly ? ", secondary hits only" : "")
                    << "): median hit rate " << 100.0 * summary.medianCacheHitRate << " %, total "
                    << 100.0 * summary.totalCacheHitRate << " %\n";
        if (result.stats.culling != "none" && !timed.empty()) {
          std::uint64_t peakBytes = 0, builds = 0, evictions = 0;
          for (const auto& frame : timed) {
            peakBytes = std::max(peakBytes, frame.blasBytes + frame.tlasBytes);
            builds += frame.blasBuilds;
            evictions += frame.blasEvictions;
          }
          const auto& last = timed.back();
          std::cout << "  culling " << result.stats.culling << ": last frame "
                    << last.activeInstances << " active, " << last.omittedInstances << " omitted, "
                    << last.inactiveInstances << " inactive instances";
          if (last.hitboxes)
            std::cout << ", " << last.activeHitboxes << " of " << last.hitboxes
                      << " hitboxes active";
          std::cout << "; peak AS " << peakBytes << " B; " << builds << " BLAS builds, "
                    << evictions << " evictions over the timed frames\n";
        }
        std::cout.flush();
        if (!csvPath.empty()) {
          csv << label << ',' << width << ',' << height << ',' << p << ',' << l << ','
              << result.stats.backend << ",\"" << result.stats.device << "\"," << timed.size()
              << ',' << medianMs << ',' << fps << ',' << summary.medianMraysPerSecond << ','
              << as.blasBytes << ',' << as.tlasBytes << ',' << as.scratchBytes << ','
              << result.stats.materialCount << ',' << result.stats.materialDispatch << ','
              << result.stats.shaderCompileMilliseconds << ','
              << result.stats.pipelineCreateMilliseconds << ',' << result.stats.cache << ','
              << result.stats.cacheEviction << ',' << result.stats.cacheEntries << ','
              << result.stats.cacheProbe << ',' << result.stats.cacheBytes << ','
              << summary.medianCacheHitRate << ',' << runLabel << ',' << w << ','
              << (staticCamera ? 0 : plan.stride) << ',' << (staticCamera ? 0 : plan.pathCameras)
              << ',' << benchSummaryCsvValues(summary) << ',' << result.stats.cacheValueFormat
              << ',' << result.stats.cacheClock << ',' << int(result.stats.cacheSnapUv) << ','
              << int(result.stats.cacheSecondaryOnly) << ',' << result.stats.cacheTile << ','
              << result.stats.culling << ',' << result.stats.shading << ','
              << wavefrontPassCsvValues(summary, result.stats) << ',' << f << ','
              << int(stoppedEarly) << '\n';
        }
        if (!framesCsv.empty()) {
          std::ostringstream perFrame;
          runtime::writeStatsCsv(perFrame, result.stats);
          outputs.emplace_back(framesCsv + fileLabel + "_" + std::to_string(width) + "x" +
                                   std::to_string(height) + ".csv",
                               perFrame.str());
        }
      }
    }
  } catch (const std::invalid_argument& e) {
    // The renderer's refusals of option combinations (e.g. --wavefront-paths when
    // --shading auto chose the megakernel): usage errors, as when the CLI catches them.
    return usageError("bench", e.what());
  } catch (const std::exception& e) {
    std::cerr << "memograph bench: " << e.what() << "\n";
    return kExitFailure;
  }
  if (!csvPath.empty())
    outputs.emplace_back(csvPath, csv.str());
  std::string error;
  if (!writeFilesAtomically(outputs, error)) {
    std::cerr << "memograph bench: " << error << "\n";
    return kExitFailure;
  }
  return kExitOk;
}
#endif

}  // namespace memograph::cli
