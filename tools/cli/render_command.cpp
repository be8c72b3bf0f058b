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
#include "runtime/host/atomic_file.h"

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "renderer_arguments.h"
#include "runtime/renderer.h"
#endif
#ifdef MEMOGRAPH_HAVE_SCENES
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#endif
#ifdef MEMOGRAPH_HAVE_IO
#include "tools/io/image_io.h"
#include "tools/io/scene_import.h"
#endif

namespace memograph::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: memograph render SCENE|builtin:NAME[:KEY=VALUE,...] --out FILE [options]\n"
    "\n"
    "Path traces a scene (thesis §5.2) and writes the accumulated HDR image. SCENE is a\n"
    "glTF/OBJ file whose material names map to DIR/<name>.mgraph (--materials DIR), or a\n"
    "built-in scene (classroom, landscape, city) with options octaves, layers, terrain, nee,\n"
    "scale, path (the city's camera: street or aerial), e.g.\n"
    "builtin:classroom:octaves=10,layers=3 (docs/scenes.md).\n"
    "\n"
    "options:\n"
    "  --out FILE            .pfm (always), .png or .exr (builds with OpenImageIO)\n"
    "  --size WxH            image size (default 640x360)\n"
    "  --paths P             paths per pixel per frame (default 1)\n"
    "  --bounces L           rays per path; 1 = primary hit with direct light (default 4)\n"
    "  --frames F            frames; a static camera accumulates them (default 1)\n"
    "  --camera-path FILE    one camera per frame: lines 'px py pz  tx ty tz  fov'\n"
    "  --environment FILE    equirectangular environment image (linear radiance, e.g. .exr,\n"
    "                        .hdr) replacing the scene's constant sky\n"
    "  --seed S              random seed (default 0)\n"
    "  --list-devices        print the Vulkan devices and their ray-tracing support\n"
    "  --materials DIR       folder of .mgraph graphs for a scene file's materials\n"
    "  --no-shader-cache     compile every shader\n"
    "  --stats FILE          per-frame statistics as CSV (GPU ms, rays, AS memory, cache)\n"
    "  --validation          enable the Vulkan validation layer\n"
    "  --debug-misses        texel cache debug view (thesis Fig. 6.9): each frame alone,\n"
    "                        red where a path of the pixel missed the cache\n"
    "  --debug-culling FILE  with --culling: also write a 512x512 top-down view of the last\n"
    "                        frame's instances (orange active, yellow omitted, grey\n"
    "                        inactive, blue outlines: inactive hitboxes; red: the camera)\n";

}  // namespace

#ifndef MEMOGRAPH_HAVE_RUNTIME
int runRender(std::span<const std::string_view>) {
  std::cerr << "memograph render: this build has no renderer (configured with "
               "MEMOGRAPH_BUILD_RUNTIME=OFF)\n";
  return kExitFailure;
}
#else

int runRender(std::span<const std::string_view> args) {
  std::string out, size = "640x360", paths = "1", bounces = "4", frames = "1", cameraPath,
                   seed = "0", materials, stats;
  bool listDevices = false, noShaderCache = false, validation = false;
  ArgumentScanner scanner("render", args);
  RendererArguments rendererArguments;
  rendererArguments.registerWith(scanner);
  scanner.option("--out", &out);
  scanner.option("-o", &out);
  scanner.option("--size", &size);
  scanner.option("--paths", &paths);
  scanner.option("--bounces", &bounces);
  scanner.option("--frames", &frames);
  scanner.option("--camera-path", &cameraPath);
  std::string environment;
  scanner.option("--environment", &environment);
  scanner.option("--seed", &seed);
  scanner.option("--materials", &materials);
  scanner.option("--stats", &stats);
  scanner.flag("--no-shader-cache", &noShaderCache);
  scanner.flag("--validation", &validation);
  bool debugMisses = false;
  scanner.flag("--debug-misses", &debugMisses);
  std::string debugCulling;
  scanner.option("--debug-culling", &debugCulling);
  scanner.flag("--list-devices", &listDevices);
  scanner.help({kHelp, kRendererHelp, kCacheHelp, kCullingHelp});
  std::vector<std::string> positional;
  if (const auto exitCode = scanner.scan(positional))
    return *exitCode;
  if (listDevices) {
    for (const auto& line : runtime::describeDevices())
      std::cout << line << "\n";
    return kExitOk;
  }
  if (positional.size() != 1)
    return usageError("render", "expected one scene");
  if (out.empty())
    return usageError("render", "--out FILE is required");

  runtime::RenderSettings settings;
  if (std::string error; !parseImageSize(size, settings.width, settings.height, error))
    return usageError("render", "--size: " + error);
  if (!parseNumber(paths, settings.pathsPerPixel) || !parseNumber(bounces, settings.raysPerPath) ||
      !parseNumber(frames, settings.frames) || !parseNumber(seed, settings.seed) ||
      settings.pathsPerPixel == 0 || settings.raysPerPath == 0 || settings.frames == 0)
    return usageError("render",
                      "--paths, --bounces and --frames take whole numbers > 0, --seed a whole "
                      "number");
  settings.sharedPrimaryRay = rendererArguments.sharedPrimary;

  // Every output is checked before any work: its format (a usage error), then its folder.
  auto imageExtension = [](const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (auto& c : extension)
      c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return extension;
  };
  auto checkImageOutput = [&](const std::string& path, std::string_view flag) {
    const std::string extension = imageExtension(path);
#ifndef MEMOGRAPH_HAVE_IO
    if (extension != ".pfm")
      return usageError("render",
                        "this build writes only .pfm (no OpenImageIO); convert it "
                        "with 'memograph' built with the io module");
#else
    if (extension != ".pfm" && extension != ".png" && extension != ".exr")
      return usageError(
          "render", std::string(flag) + " must name a .pfm, .png or .exr file, not '" + path + "'");
#endif
    return checkOutputFile("render", path);
  };
  if (const int code = checkImageOutput(out, "--out"); code != kExitOk)
    return code;
  if (!debugCulling.empty()) {
    if (const int code = checkImageOutput(debugCulling, "--debug-culling"); code != kExitOk)
      return code;
    if (std::filesystem::path(debugCulling) == std::filesystem::path(out))
      return usageError("render", "--debug-culling and --out name the same file");
  }
  if (!stats.empty()) {
    if (const int code = checkOutputFile("render", stats); code != kExitOk)
      return code;
    if (std::filesystem::path(stats) == std::filesystem::path(out))
      return usageError("render", "--stats and --out name the same file");
  }

  runtime::RendererOptions options;
  try {
    options = rendererArguments.parse();
  } catch (const std::invalid_argument& e) {
    return usageError("render", e.what());
  }
  for (const std::string& line : RendererArguments::ignoredOptions(scanner, options))
    std::cerr << "memograph render: " << line << "\n";
  options.context.validation = validation;
  if (debugMisses && options.cache.mode == runtime::CacheMode::None)
    return usageError("render", "--debug-misses shows cache misses; it needs --cache texel");
  options.debugCacheMisses = debugMisses;
  if (!debugCulling.empty()) {
    if (options.culling.mode == runtime::CullingMode::None)
      return usageError("render",
                        "--debug-culling shows which instances culling keeps; it needs "
                        "--culling frustum or --culling lipac");
    options.debugCullingSize = 512;
  }
  options.shaderCache = !noShaderCache;

  // The scene: built-in, or a file through the io module.
  runtime::Scene scene;
  compiler::Diagnostics diagnostics;
  const std::string& name = positional[0];
  if (name.rfind("builtin:", 0) == 0) {
#ifdef MEMOGRAPH_HAVE_SCENES
    std::string error;
    auto spec = runtime::parseBuiltinSceneSpec(std::string_view(name).substr(8), error);
    if (!spec)
      return usageError("render", error);
    try {
      scene = runtime::makeBuiltinScene(spec->name, spec->options);
    } catch (const std::invalid_argument& e) {
      std::cerr << "memograph render: " << e.what() << "\n";
      return kExitFailure;
    }
#else
    std::cerr << "memograph render: this build has no built-in scenes\n";
    return kExitFailure;
#endif
  } else {
#ifdef MEMOGRAPH_HAVE_IO
    auto imported = io::importScene(name, materials, diagnostics);
    printDiagnostics(diagnostics);
    if (!imported)
      return kExitFailure;
    scene = std::move(*imported);
#else
    std::cerr << "memograph render: this build reads no scene files (no assimp); use a "
                 "builtin: scene\n";
    return kExitFailure;
#endif
  }
  if (options.shading == runtime::Shading::Wavefront && !scene.animatedMeshes.empty())
    return usageError("render", "--shading wavefront renders static scenes only; " + name +
                                    " has animated meshes");
#ifdef MEMOGRAPH_HAVE_IO
  options.textureLoader = [](const std::string& path) {
    compiler::Diagnostics textureDiagnostics;
    auto image = io::readImageFloat(path, textureDiagnostics);
    if (!image)
      throw std::runtime_error(compiler::formatDiagnostics(textureDiagnostics));
    return runtime::TextureImage{{std::move(*image)}};
  };
#endif
  // A scene may name its own environment image (the Blender export's world): --environment
  // replaces it.
  // Unused in builds without the io module, which read no environment image.
  [[maybe_unused]] float environmentStrength = 1.0f, environmentUOffset = 0.0f;
  if (environment.empty() && !scene.environment.imagePath.empty() &&
      scene.environment.imageRgb.empty()) {
    environment = scene.environment.imagePath;
    environmentStrength = scene.environment.imageStrength;
    environmentUOffset = scene.environment.imageUOffset;
  }
  if (!environment.empty()) {
#ifdef MEMOGRAPH_HAVE_IO
    auto image = io::readImageFloat(environment, diagnostics);
    if (!image) {
      printDiagnostics(diagnostics);
      return kExitFailure;
    }
    auto& env = scene.environment;
    env.imagePath = environment;
    env.imageWidth = static_cast<std::uint32_t>(image->width);
    env.imageHeight = static_cast<std::uint32_t>(image->height);
    env.imageRgb.clear();
    env.imageRgb.reserve(std::size_t(image->width) * image->height * 3);
    const std::size_t w = image->width,
                      shift = std::size_t(std::lround(environmentUOffset * float(w))) % (w ? w : 1);
    for (std::size_t y = 0; y < std::size_t(image->height); ++y) {
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t i = 4 * (y * w + (x + shift) % w);
        env.imageRgb.insert(env.imageRgb.end(), {environmentStrength * image->rgba[i],
                                                 environmentStrength * image->rgba[i + 1],
                                                 environmentStrength * image->rgba[i + 2]});
      }
    }
#else
    std::cerr << "memograph render: this build reads no images (no OpenImageIO)\n";
    return kExitFailure;
#endif
  }
  if (rendererArguments.noEmissiveNee)
    scene.emissiveLightSampling = false;
  if (!cameraPath.empty()) {
#ifdef MEMOGRAPH_HAVE_SCENES
    auto path = runtime::loadCameraPath(cameraPath, diagnostics);
    if (!path) {
      printDiagnostics(diagnostics);
      return kExitFailure;
    }
    settings.cameraPath = path->frames;
#else
    std::cerr << "memograph render: this build reads no camera paths\n";
    return kExitFailure;
#endif
  }

  const bool progress = isatty(STDERR_FILENO) && settings.frames > 1;
  settings.onFrame = [&](const runtime::FrameStats& frame) {
    if (!progress)
      return;
    int done = int(40.0 * (frame.frame + 1) / settings.frames);
    std::fprintf(stderr, "\r[%-40s] frame %u/%u  %.2f ms", std::string(done, '#').c_str(),
                 frame.frame + 1, settings.frames, frame.gpuMilliseconds);
    if (frame.frame + 1 == settings.frames)
      std::fprintf(stderr, "\n");
  };

  try {
    // Many materials: per-material callables (pipeline backend) unless --backend says otherwise.
    options.context.autoPrefersPipeline =
        runtime::countDistinctMaterialGraphs(scene) > runtime::kManyMaterialGraphs;
    runtime::Renderer renderer(options);
    runtime::RenderResult result = renderer.render(scene, settings);
    for (const auto& error : renderer.context().validationErrors())
      std::cerr << "validation: " << error << "\n";
    // The image and the statistics are one output set (files::commitFileSet): both are
    // written, or neither, so a failing --stats no longer leaves the image behind.
    std::vector<files::StagedFile> staged;
    std::string error;
    auto stage = [&](const std::string& path, const runtime::HdrImage& image) {
      files::StagedFile& file = staged.emplace_back();
      if (imageExtension(path) == ".pfm") {
        if (!file.create(path, error) || !file.write(runtime::encodePfm(image), error)) {
          std::cerr << "memograph render: " << path << ": " << error << "\n";
          return false;
        }
        return true;
      }
#ifdef MEMOGRAPH_HAVE_IO
      if (!io::stageImage(path, image, io::LdrOptions{}, file, diagnostics)) {
        printDiagnostics(diagnostics);
        return false;
      }
#endif
      return true;
    };
    staged.reserve(3);
    if (!stage(out, result.image))
      return kExitFailure;
    if (!debugCulling.empty() && !stage(debugCulling, result.cullingView))
      return kExitFailure;
    if (!stats.empty()) {
      std::ostringstream csv;
      runtime::writeStatsCsv(csv, result.stats);
      files::StagedFile& file = staged.emplace_back();
      if (!file.create(stats, error) || !file.write(csv.str(), error)) {
        std::cerr << "memograph render: " << stats << ": " << error << "\n";
        return kExitFailure;
      }
    }
    if (!files::commitFileSet(staged, error)) {
      std::cerr << "memograph render: " << error << "\n";
      return kExitFailure;
    }
    std::cerr << "rendered " << out << " on " << result.stats.device << " (" << result.stats.backend
              << ", " << result.stats.materialDispatch << " materials"
              << ", " << result.stats.shading << "): median "
              << result.stats.medianGpuMilliseconds() << " ms per frame; shaders "
              << result.stats.shadersCompiled << " compiled in "
              << result.stats.shaderCompileMilliseconds << " ms, pipeline "
              << result.stats.pipelineCreateMilliseconds << " ms\n";
    if (result.stats.cache != "none" && !result.stats.frames.empty()) {
      const auto& last = result.stats.frames.back();
      std::cerr << result.stats.cache << " cache"
                << (result.stats.cacheTile.empty() ? "" : " (" + result.stats.cacheTile + ")")
                << ": " << result.stats.cacheEntriesText() << " (" << result.stats.cacheBytes
                << " B, " << result.stats.cacheValueFormat << ", clock " << result.stats.cacheClock
                << "); last frame " << last.cacheLookups << " lookups, " << last.cacheHits
                << " hits (" << 100.0 * last.cacheHitRate() << " %), " << last.cacheOccupancy
                << " entries in use";
      if (result.stats.cache == "tile")
        std::cerr << ", " << last.cacheTilesComputed << " tiles computed ("
                  << last.cacheDuplicateTiles << " duplicates)";
      std::cerr << "\n";
    }
    if (result.stats.culling != "none" && !result.stats.frames.empty()) {
      const auto& last = result.stats.frames.back();
      std::cerr << "culling " << result.stats.culling << ": last frame " << last.activeInstances
                << " active, " << last.omittedInstances << " omitted, " << last.inactiveInstances
                << " inactive instances; AS " << last.blasBytes + last.tlasBytes
                << " B resident (peak BLAS " << result.stats.accelerationStructures.blasBytes
                << " B)\n";
    }
  } catch (const std::invalid_argument& e) {
    // The renderer's refusals of option combinations (e.g. --wavefront-paths when
    // --shading auto chose the megakernel): usage errors, as when the CLI catches them.
    return usageError("render", e.what());
  } catch (const std::exception& e) {
    std::cerr << "memograph render: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}
#endif

}  // namespace memograph::cli
