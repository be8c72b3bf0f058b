// memograph render SCENE|builtin:NAME ... --out FILE: renders a scene with the path tracer
// (runtime/) and writes the HDR image (.pfm always; .png/.exr when built with the io
// module) and, with --stats, the per-frame statistics as CSV.
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "frame_files.h"
#include "runtime/host/atomic_file.h"
#include "scene_inputs.h"

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "option_table.h"
#include "runtime/renderer.h"
#include "runtime/scene/pack/scene_pack.h"
#endif
#ifdef MEMOGRAPH_HAVE_SCENES
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#include "runtime/scene/scene_limits.h"
#include "runtime/trace/render_setup.h"
#endif
#ifdef MEMOGRAPH_HAVE_IO
#include "tools/io/image_io.h"
#include "tools/io/scene_import.h"
#endif

namespace memograph::cli {

#ifndef MEMOGRAPH_HAVE_RUNTIME
int runRender(std::span<const std::string_view>) {
  std::cerr << "memograph render: this build has no renderer (configured with "
               "MEMOGRAPH_BUILD_RUNTIME=OFF)\n";
  return kExitFailure;
}
#else

namespace {

constexpr std::string_view kIntro =
    "usage: memograph render SCENE|builtin:NAME[:KEY=VALUE,...] --out FILE [options]\n"
    "\n"
    "Path traces a scene (thesis §5.2) and writes the accumulated HDR image. SCENE is a\n"
    "glTF/OBJ file whose material names map to DIR/<name>.mgraph (--materials DIR), a scene\n"
    "pack (.mgpack, written by 'memograph pack'; its camera path is followed unless\n"
    "--camera-path is given), or a built-in scene (classroom, landscape, city) with\n"
    "options octaves, layers, terrain, nee, scale, path (the city's camera: street or\n"
    "aerial), ao and bevel (samples of an Ambient Occlusion and a Bevel node in every\n"
    "material; default 0, none), e.g. builtin:classroom:octaves=10,layers=3\n"
    "(docs/guide/scenes.md).\n";

std::string imageExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (auto& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// An image output's format: one this build writes, else a usage error.
int checkImageFormat(const std::string& path, std::string_view flag) {
  const std::string extension = imageExtension(path);
#ifndef MEMOGRAPH_HAVE_IO
  (void)flag;
  if (extension != ".pfm")
    return usageError("render",
                      "this build writes only .pfm (no OpenImageIO); convert it "
                      "with 'memograph' built with the io module");
#else
  if (extension != ".pfm" && extension != ".png" && extension != ".exr")
    return usageError(
        "render", std::string(flag) + " must name a .pfm, .png or .exr file, not '" + path + "'");
#endif
  return kExitOk;
}

// The outputs' usage errors, before anything is read: formats, an output over an input or
// over another output, a --device past the last.
int checkOutputNames(const std::string& sceneName, const TraceCommandOptions& options) {
  if (const int code = checkImageFormat(options.out, "--out"); code != kExitOk)
    return code;
  if (!options.debugCulling.empty()) {
    if (const int code = checkImageFormat(options.debugCulling, "--debug-culling"); code != kExitOk)
      return code;
  }
  // What the render reads: the scene file, the images and paths named, the graphs of the
  // scene's materials and the node library (the scene's own buffers and textures are
  // known only once it is read).
  std::vector<CommandFile> inputs = {
      {"SCENE", sceneName.rfind("builtin:", 0) == 0 ? std::string() : sceneName},
      {"--environment", options.environment},
      {"--camera-path", options.cameraPath}};
  addFolderInputs(inputs, "--materials graph", options.materials, ".mgraph", false);
  addFolderInputs(inputs, "--nodes file", options.renderer.nodeLibraryDirectory, ".inc", true);
  if (const int code = refuseOutputOverInput("render",
                                             {{"--out", options.out},
                                              {"--debug-culling", options.debugCulling},
                                              {"--stats", options.stats}},
                                             inputs);
      code != kExitOk)
    return code;
  return checkDeviceIndex("render", options.renderer.context.deviceIndex);
}

// The outputs' folders (kExitFailure), checked once the scene is loaded, whose usage errors
// (a built-in scene's ranges) come first so that
// a command line with both problems is named a usage error whichever comes first on it.
int checkOutputFolders(const TraceCommandOptions& options) {
  for (const std::string* path : {&options.out, &options.debugCulling, &options.stats}) {
    if (path->empty())
      continue;
    if (const int code = checkOutputFile("render", *path); code != kExitOk)
      return code;
  }
  return kExitOk;
}

// The checks across options, the notes for unused ones, and the debug views' needs.
int checkModes(TraceCommandOptions& options) {
  try {
    validateTraceOptions(options);
  } catch (const std::invalid_argument& e) {
    return usageError("render", e.what());
  }
  for (const std::string& line : ignoredOptionNotes(options))
    std::cerr << "memograph render: " << line << "\n";
  runtime::RendererOptions& renderer = options.renderer;
  if (options.debugMisses && renderer.cache.mode == runtime::CacheMode::None)
    return usageError("render", "--debug-misses shows cache misses; it needs --cache texel");
  renderer.debugCacheMisses = options.debugMisses;
  if (!options.debugCulling.empty()) {
    if (renderer.culling.mode == runtime::CullingMode::None)
      return usageError("render",
                        "--debug-culling shows which instances culling keeps; it needs "
                        "--culling frustum or --culling lipac");
    renderer.debugCullingSize = 512;
  }
  return kExitOk;
}

// --frame-range's usage errors: the options it replaces or cannot share a run with, and an
// --out that names the frames apart. Sets `pattern`.
int checkFrameRange(const TraceCommandOptions& options, FramePattern& pattern) {
  if (!options.frameRange) {
    if (options.resume)
      return usageError("render",
                        "--resume skips the finished frames of a --frame-range; "
                        "it needs --frame-range");
    if (options.wasGiven("--warmup-frames"))
      std::cerr << "memograph render: " << ignoredOptionNote("--warmup-frames", "--frame-range")
                << "\n";
    return kExitOk;
  }
  if (options.wasGiven("--frames"))
    return usageError("render",
                      "--frames accumulates one image over frames; with --frame-range each "
                      "frame is an image of its own (--paths sets its samples)");
  if (!options.stats.empty() || !options.debugCulling.empty())
    return usageError("render",
                      "--stats and --debug-culling describe one image's render; a "
                      "--frame-range writes only its frames");
  std::string error;
  const auto parsed = parseFramePattern(options.out, error);
  if (!parsed)
    return usageError("render", error);
  pattern = *parsed;
  const FrameRange range = *options.frameRange;
  if (pattern.hashesAt == std::string::npos && range.first != range.last)
    return usageError("render", "--out '" + options.out + "' names one file for the " +
                                    std::to_string(range.last - range.first + 1) +
                                    " frames of --frame-range; put a run of '#' in its file name "
                                    "for the frame's index (e.g. frame_####.pfm)");
  return kExitOk;
}

// A range past the camera path's end: the path's last frame is the one the user meant to end
// on, not a camera repeated (what a render of more frames than cameras does).
int checkRangeOnPath(const TraceCommandOptions& options) {
  const std::size_t cameras = options.settings.cameraPath.size();
  if (!options.frameRange || cameras == 0 || options.frameRange->last < cameras)
    return kExitOk;
  return usageError("render", "--frame-range " + std::to_string(options.frameRange->first) + ":" +
                                  std::to_string(options.frameRange->last) +
                                  " ends past the camera path's last frame, " +
                                  std::to_string(cameras - 1) + " (frames 0.." +
                                  std::to_string(cameras - 1) + ")");
}

// The scene: built-in, a scene pack (which sets the camera path and the texture loader), or
// a file through the io module.
int loadScene(const std::string& name, TraceCommandOptions& options, runtime::Scene& scene) {
  if (runtime::isScenePackPath(name)) {
    if (const int code =
            loadScenePackFile("render", name, options, scene, options.settings.cameraPath);
        code != kExitOk)
      return code;
  } else if (name.rfind("builtin:", 0) == 0) {
#ifdef MEMOGRAPH_HAVE_SCENES
    std::string error;
    auto spec = runtime::parseBuiltinSceneSpec(std::string_view(name).substr(8), error);
    if (!spec)
      return usageError("render", error);
    spec->options.onGeometry = runtime::deviceGeometryCheck(options.renderer.context);
    spec->options.meshLods = options.renderer.culling.showsMeshLods();
    try {
      scene = runtime::makeBuiltinScene(spec->name, spec->options);
    } catch (const std::invalid_argument& e) {
      // An unknown name or a value out of range: the command line's, as in bench.
      return usageError("render", e.what());
    } catch (const runtime::SceneLimitError& e) {
      // Too large for the device: refused while the scene is built (exit 1).
      std::cerr << "memograph render: " << e.what() << "\n";
      return kExitFailure;
    }
#else
    std::cerr << "memograph render: this build has no built-in scenes\n";
    return kExitFailure;
#endif
  } else {
#ifdef MEMOGRAPH_HAVE_IO
    compiler::Diagnostics diagnostics;
    auto imported = io::importScene(name, options.materials, diagnostics);
    printDiagnostics(diagnostics);
    if (!imported)
      return kExitFailure;
    scene = std::move(*imported);
#else
    std::cerr << "memograph render: this build reads no scene files (no assimp); use a "
                 "builtin: scene or a scene pack (.mgpack, 'memograph pack')\n";
    return kExitFailure;
#endif
  }
  if (options.noEmissiveNee)
    scene.emissiveLightSampling = false;
  return kExitOk;
}

int loadCameraPath(const std::string& file, runtime::RenderSettings& settings) {
  if (file.empty())
    return kExitOk;
#ifdef MEMOGRAPH_HAVE_SCENES
  compiler::Diagnostics diagnostics;
  auto path = runtime::loadCameraPath(file, diagnostics);
  if (!path) {
    printDiagnostics(diagnostics);
    return kExitFailure;
  }
  settings.cameraPath = path->frames;
  return kExitOk;
#else
  (void)settings;
  std::cerr << "memograph render: this build reads no camera paths\n";
  return kExitFailure;
#endif
}

void useTextureLoader([[maybe_unused]] runtime::RendererOptions& renderer) {
#ifdef MEMOGRAPH_HAVE_IO
  renderer.textureLoader = [](const std::string& path) {
    compiler::Diagnostics textureDiagnostics;
    auto image = io::readImageFloat(path, textureDiagnostics);
    if (!image)
      throw std::runtime_error(compiler::formatDiagnostics(textureDiagnostics));
    return runtime::TextureImage{{std::move(*image)}};
  };
#endif
}

// A progress bar on a terminal, for renders of more than one frame.
void showProgress(runtime::RenderSettings& settings) {
  if (!isatty(STDERR_FILENO) || settings.frames <= 1)
    return;
  const std::uint32_t frames = settings.frames, first = settings.firstFrame;
  settings.onFrame = [frames, first](const runtime::FrameStats& frame) {
    const std::uint32_t rendered = frame.frame - first + 1;
    int done = int(40.0 * rendered / frames);
    std::fprintf(stderr, "\r[%-40s] frame %u/%u  %.2f ms", std::string(done, '#').c_str(), rendered,
                 frames, frame.gpuMilliseconds);
    if (rendered == frames)
      std::fprintf(stderr, "\n");
  };
}

// Stages `image` as `path` (its format by the extension) into `file`; false after saying why.
bool stageImageFile(const std::string& path, const runtime::HdrImage& image,
                    files::StagedFile& file) {
  if (imageExtension(path) == ".pfm") {
    std::string error;
    if (!file.create(path, error) || !file.write(runtime::encodePfm(image), error)) {
      std::cerr << "memograph render: " << path << ": " << error << "\n";
      return false;
    }
    return true;
  }
#ifdef MEMOGRAPH_HAVE_IO
  compiler::Diagnostics diagnostics;
  if (!io::stageImage(path, image, io::LdrOptions{}, file, diagnostics)) {
    printDiagnostics(diagnostics);
    return false;
  }
#endif
  return true;
}

// The image, the top view and the statistics are one output set (files::commitFileSet):
// all are written, or none.
int writeOutputs(const TraceCommandOptions& options, const runtime::RenderResult& result) {
  std::vector<files::StagedFile> staged;
  std::string error;
  auto stage = [&](const std::string& path, const runtime::HdrImage& image) {
    return stageImageFile(path, image, staged.emplace_back());
  };
  staged.reserve(3);
  if (!stage(options.out, result.image))
    return kExitFailure;
  if (!options.debugCulling.empty() && !stage(options.debugCulling, result.cullingView))
    return kExitFailure;
  if (!options.stats.empty()) {
    std::ostringstream csv;
    runtime::writeStatsCsv(csv, result.stats);
    files::StagedFile& file = staged.emplace_back();
    if (!file.create(options.stats, error) || !file.write(csv.str(), error)) {
      std::cerr << "memograph render: " << options.stats << ": " << error << "\n";
      return kExitFailure;
    }
  }
  if (!files::commitFileSet(staged, error)) {
    std::cerr << "memograph render: " << error << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

void printSummary(const std::string& out, const runtime::RenderStats& stats) {
  std::cerr << "rendered " << out << " on " << stats.device << " (" << stats.backend << ", "
            << stats.materialDispatch << " materials"
            << ", " << stats.shading << "): median " << stats.medianGpuMilliseconds()
            << " ms per frame; shaders " << stats.shadersCompiled << " compiled in "
            << stats.shaderCompileMilliseconds << " ms, pipeline "
            << stats.pipelineCreateMilliseconds << " ms (" << runtime::pipelineCacheText(stats)
            << "); first frame done " << stats.firstFrameMilliseconds
            << " ms after the render began\n";
  if (stats.wavefrontMaterialPasses > 0)
    std::cerr << "wavefront material passes: " << stats.wavefrontMaterialPasses << ", "
              << stats.wavefrontMaterialInlinedInstructions
              << " SPIR-V instructions with every call inlined, "
              << stats.wavefrontMaterialGraphInstructions << " of them one copy of each graph; "
              << "at most " << stats.wavefrontMaterialGraphCopiesMax
              << " copies of a graph a pass\n";
  if (stats.ambientOcclusionSamples > 0)
    std::cerr << "ambient occlusion (seeds/004 §3): " << stats.ambientOcclusionSamples
              << " rays of length " << stats.ambientOcclusionDistance
              << " from each path's primary hit\n";
  if (stats.cache != "none" && !stats.frames.empty()) {
    const auto& last = stats.frames.back();
    std::cerr << stats.cache << " cache"
              << (stats.cacheTile.empty() ? "" : " (" + stats.cacheTile + ")") << ": "
              << stats.cacheEntriesText() << " (" << stats.cacheBytes << " B, "
              << stats.cacheValueFormat << ", clock " << stats.cacheClock
              << (stats.cacheRefresh.empty() ? "" : ", " + stats.cacheRefresh) << "); last frame "
              << last.cacheLookups << " lookups, " << last.cacheHits << " hits ("
              << 100.0 * last.cacheHitRate() << " %), " << last.cacheOccupancy << " entries in use";
    if (stats.cache == "tile")
      std::cerr << ", " << last.cacheTilesComputed << " tiles computed ("
                << last.cacheDuplicateTiles << " duplicates)";
    std::cerr << "\n";
  }
  if (stats.culling != "none" && !stats.frames.empty()) {
    const auto& last = stats.frames.back();
    std::cerr << "culling " << stats.culling << ": last frame " << last.activeInstances
              << " active, " << last.omittedInstances << " omitted, " << last.inactiveInstances
              << " inactive instances; AS " << last.blasBytes + last.tlasBytes
              << " B resident (peak BLAS " << stats.accelerationStructures.blasBytes << " B)\n";
  }
}

// Renders `scene` with `settings` and hands the result to `finish`, whose exit code it
// returns; the renderer's errors become the command's.
template <typename Finish>
int renderScene(TraceCommandOptions& options, const runtime::Scene& scene,
                const runtime::RenderSettings& settings, Finish&& finish) {
  try {
    // Many materials: per-material callables (pipeline backend) unless --backend says otherwise.
    options.renderer.context.autoPrefersPipeline =
        runtime::countDistinctMaterialGraphs(scene) > runtime::kManyMaterialGraphs;
    runtime::Renderer renderer(options.renderer);
    runtime::RenderResult result = renderer.render(scene, settings);
    for (const auto& error : renderer.context().validationErrors())
      std::cerr << "validation: " << error << "\n";
    return finish(result);
  } catch (const std::invalid_argument& e) {
    // The renderer's refusals of option combinations (e.g. --wavefront-paths when
    // --shading auto chose the megakernel): usage errors, as when the CLI catches them.
    return usageError("render", e.what());
  } catch (const std::exception& e) {
    std::cerr << "memograph render: " << e.what() << "\n";
    return kExitFailure;
  }
}

// Renders `scene` and writes the outputs.
int renderAndWrite(TraceCommandOptions& options, const runtime::Scene& scene) {
  return renderScene(options, scene, options.settings, [&](const runtime::RenderResult& result) {
    if (const int code = writeOutputs(options, result); code != kExitOk)
      return code;
    printSummary(options.out, result.stats);
    return kExitOk;
  });
}

// What a frame range renders: the frames to write (all of the range, or with --resume those
// whose files are not complete) and the frames before them that warm the state a frame
// inherits. Returns false where nothing is left to render.
struct RangePlan {
  std::vector<bool> write;  // by frame - range.first
  std::uint32_t firstRendered = 0, lastRendered = 0, warmup = 0, skipped = 0;
  // No state crosses frames (no cache, no LiPaC): a finished frame between missing ones is
  // skipped, not rendered again.
  bool framesIndependent = true;
};

bool planRange(const TraceCommandOptions& options, const FramePattern& pattern, RangePlan& plan) {
  const FrameRange range = *options.frameRange;
  plan.write.assign(std::size_t(range.last - range.first) + 1, true);
  std::optional<std::uint32_t> first, last;
  for (std::uint32_t f = range.first;; ++f) {
    if (options.resume && imageFileComplete(framePath(pattern, f))) {
      plan.write[f - range.first] = false;
      ++plan.skipped;
    } else {
      first = first.value_or(f);
      last = f;
    }
    if (f == range.last)
      break;
  }
  if (!first)
    return false;
  // Only the cache and LiPaC carry state from frame to frame; without them a frame is the
  // same rendered alone, and warming would cost frames for nothing.
  const runtime::RendererOptions& renderer = options.renderer;
  const bool carriesState = renderer.cache.mode != runtime::CacheMode::None ||
                            renderer.culling.mode == runtime::CullingMode::Lipac;
  plan.framesIndependent = !carriesState;
  plan.warmup = carriesState ? std::min(*first, options.warmupFrames) : 0;
  plan.firstRendered = *first - plan.warmup;
  plan.lastRendered = *last;
  return true;
}

// Renders frames of a --frame-range and writes each as it is done, each file on its own
// (a frame is all or nothing; a preempted job keeps the frames it finished).
int renderFrameRange(TraceCommandOptions& options, const runtime::Scene& scene,
                     const FramePattern& pattern) {
  const FrameRange range = *options.frameRange;
  RangePlan plan;
  if (!planRange(options, pattern, plan)) {
    std::cerr << "memograph render: frames " << range.first << ".." << range.last
              << " are all complete; nothing to render\n";
    return kExitOk;
  }
  runtime::RenderSettings& settings = options.settings;
  settings.firstFrame = plan.firstRendered;
  settings.frames = plan.lastRendered - plan.firstRendered + 1;
  settings.eachFrameAlone = true;
  settings.frameImageWanted = [&](std::uint32_t f) {
    return f >= range.first && f <= range.last && plan.write[f - range.first];
  };
  if (plan.framesIndependent)
    settings.skipFrame = [&](std::uint32_t f) { return !settings.frameImageWanted(f); };
  std::uint32_t written = 0;
  settings.onFrameImage = [&](std::uint32_t f, const runtime::HdrImage& image) {
    const std::string path = framePath(pattern, f);
    files::StagedFile file;
    std::string error;
    if (!stageImageFile(path, image, file) || !file.commit(error))
      throw std::runtime_error(error.empty() ? "frame " + std::to_string(f) + " not written"
                                             : path + ": " + error);
    ++written;
  };
  showProgress(settings);
  return renderScene(options, scene, settings, [&](const runtime::RenderResult& result) {
    std::cerr << "frames " << range.first << ".." << range.last << ": " << written << " written, "
              << plan.skipped << " complete already, " << plan.warmup
              << " warm-up frames rendered first; " << result.stats.frames.size()
              << " frames rendered in all\n";
    printSummary(framePath(pattern, plan.lastRendered), result.stats);
    return kExitOk;
  });
}

}  // namespace

int runRender(std::span<const std::string_view> args) {
  TraceCommandOptions options;
  std::vector<std::string> positional;
  if (const auto exitCode =
          scanTraceOptions(TraceCommand::Render, args, kIntro, options, positional))
    return *exitCode;
  if (options.listDevices) {
    for (const auto& line : runtime::describeDevices())
      std::cout << line << "\n";
    return kExitOk;
  }
  if (positional.size() != 1)
    return usageError("render", "expected one scene");
  if (options.out.empty())
    return usageError("render", "--out FILE is required");
  if (const int code = checkModes(options); code != kExitOk)
    return code;
  FramePattern pattern;
  if (const int code = checkFrameRange(options, pattern); code != kExitOk)
    return code;
  if (const int code = checkOutputNames(positional[0], options); code != kExitOk)
    return code;
  runtime::Scene scene;
  if (const int code = loadScene(positional[0], options, scene); code != kExitOk)
    return code;
  if (const int code = checkOutputFolders(options); code != kExitOk)
    return code;
  if (const int code = loadEnvironmentImage("render", options.environment, scene); code != kExitOk)
    return code;
  if (const int code = loadCameraPath(options.cameraPath, options.settings); code != kExitOk)
    return code;
  if (const int code = checkRangeOnPath(options); code != kExitOk)
    return code;
  if (!runtime::isScenePackPath(positional[0]))
    useTextureLoader(options.renderer);
  if (options.frameRange)
    return renderFrameRange(options, scene, pattern);
  showProgress(options.settings);
  return renderAndWrite(options, scene);
}
#endif

}  // namespace memograph::cli
