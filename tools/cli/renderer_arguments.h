// The renderer's command-line options that `render` and `bench` share: trace backend,
// material dispatch, device, node library, shader cache folder, shared primary ray, emissive
// NEE, the material cache's options (cache_arguments.h) and culling's (culling_arguments.h),
// with their help text (each command prints its own options, then kRendererHelp, then
// kCacheHelp and kCullingHelp).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cache_arguments.h"
#include "cli_common.h"
#include "culling_arguments.h"
#include "runtime/renderer.h"

namespace memograph::cli {

inline constexpr const char* kRendererHelp =
    "  --backend B           auto (default: query, or pipeline for scenes of more than 8\n"
    "                        distinct materials, where it has callables), query, pipeline\n"
    "  --material-dispatch D auto (default), switch or callable: how the path tracer\n"
    "                        reaches each material. switch: every material in the one\n"
    "                        path-tracer shader; callable: one callable shader per material\n"
    "                        (pipeline backend only; keeps many-material scenes such as\n"
    "                        the classroom compilable). auto: callable on the pipeline\n"
    "                        backend, switch on the query backend\n"
    "  --device N            Vulkan device index (render --list-devices lists them)\n"
    "  --nodes DIR           node library folder instead of the built-in one\n"
    "  --shader-cache DIR    SPIR-V cache folder (default $XDG_CACHE_HOME/memograph)\n"
    "  --shared-primary      one primary ray through the pixel centre for all P paths of a\n"
    "                        pixel (thesis §5.1)\n"
    "  --no-emissive-nee     no light sampling of emissive triangles (BSDF rays only)\n"
    "  --shading S           auto (default), megakernel or wavefront. megakernel: one kernel\n"
    "                        runs each path to its end; wavefront: passes over queues of\n"
    "                        paths, their state in memory, materials evaluated in batches\n"
    "                        sorted by material (a prototype: both caches, tiles always by\n"
    "                        the deferred fill's queue; no culling, debug views, animated\n"
    "                        meshes or emitters NEE must evaluate). auto: the wavefront on a\n"
    "                        GPU (faster in every configuration measured on an H200, e.g.\n"
    "                        the classroom uncached 96.7 against 2762 ms) when it does all\n"
    "                        that is asked, else the megakernel (on a CPU too)\n"
    "  --wavefront-paths N   the wavefront's paths in flight (its path state's slots; 0, the\n"
    "                        default: every pixel, or what the device's storage-buffer range\n"
    "                        holds); a round over more pixels runs in chunks of N. Needs\n"
    "                        the wavefront: --shading wavefront, or auto choosing it\n"
    "  --dispatch-paths N    the megakernel traces a frame's P paths per pixel in trace\n"
    "                        dispatches of at most N paths each, each adding its share of\n"
    "                        the pixel's mean (default 5: at P = 6 a frame in two took\n"
    "                        0.935x the time of one on an H100; 0: all P in one). With\n"
    "                        --shared-primary each dispatch traces the primary ray again\n";

struct RendererArguments {
  CacheArguments cache;
  CullingArguments culling;
  std::string backend = "auto", materialDispatch = "auto", device = "-1", nodes, shaderCache,
              shading = "auto", wavefrontPaths = "0", dispatchPaths;
  bool sharedPrimary = false;
  // A scene option, not a renderer one: the command applies it to each scene it loads.
  bool noEmissiveNee = false;

  void registerWith(ArgumentScanner& scanner) {
    cache.registerWith(scanner);
    culling.registerWith(scanner);
    scanner.option("--backend", &backend);
    scanner.option("--material-dispatch", &materialDispatch);
    scanner.option("--device", &device);
    scanner.option("--nodes", &nodes);
    scanner.option("--shader-cache", &shaderCache);
    scanner.flag("--shared-primary", &sharedPrimary);
    scanner.flag("--no-emissive-nee", &noEmissiveNee);
    scanner.option("--shading", &shading);
    scanner.option("--wavefront-paths", &wavefrontPaths);
    scanner.option("--dispatch-paths", &dispatchPaths);
  }

  // A note for each option given that `options` leave unused (LiPaC's without --culling
  // lipac, the caches' without --cache, ...): the command prints them and goes on, so that a
  // forgotten mode does not silently measure something else.
  static std::vector<std::string> ignoredOptions(const ArgumentScanner& scanner,
                                                 const runtime::RendererOptions& options) {
    std::vector<std::string> notes = CullingArguments::ignored(scanner, options.culling.mode);
    for (std::string& note : CacheArguments::ignored(scanner, options.cache.mode))
      notes.push_back(std::move(note));
    if (scanner.given("--dispatch-paths") && options.shading == runtime::Shading::Wavefront)
      notes.push_back(ignoredOptionNote("--dispatch-paths", "the megakernel"));
    return notes;
  }

  // The renderer's options (the command adds its own, e.g. validation). Throws
  // std::invalid_argument with a message for the user.
  runtime::RendererOptions parse() const {
    runtime::RendererOptions options;
    options.context.backend = runtime::parseBackend(backend);
    options.materialDispatch = runtime::parseMaterialDispatch(materialDispatch);
    options.cache = cache.parse();
    options.floorMaterials = cache.floorMaterials;
    options.culling = culling.parse();
    std::uint32_t deviceIndex = 0;
    if (device != "-1" && !parseNumber(device, deviceIndex))
      throw std::invalid_argument(
          "--device takes a device index (memograph render "
          "--list-devices lists them), not '" +
          device + "'");
    options.context.deviceIndex = device == "-1" ? -1 : int(deviceIndex);
    options.shaderCacheDirectory = shaderCache;
    options.nodeLibraryDirectory = nodes;
    options.shading = runtime::parseShading(shading);
    if (!parseNumber(wavefrontPaths, options.wavefrontPaths))
      throw std::invalid_argument(
          "--wavefront-paths takes a number of paths (0: the default), "
          "not '" +
          wavefrontPaths + "'");
    if (!dispatchPaths.empty() && !parseNumber(dispatchPaths, options.pathsPerDispatch))
      throw std::invalid_argument(
          "--dispatch-paths takes a number of paths per trace dispatch (0: all in one), not '" +
          dispatchPaths + "'");
    runtime::validateWavefrontOptions(options);
    if (options.shading == runtime::Shading::Wavefront && cache.tileFill == "subgroup")
      throw std::invalid_argument(
          "--tile-fill subgroup is the megakernel's: --shading wavefront computes missing "
          "tiles in its material passes, from the deferred fill's queue");
    return options;
  }
};

}  // namespace memograph::cli
