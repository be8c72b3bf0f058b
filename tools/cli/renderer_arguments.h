// The renderer's command-line options that `render` and `bench` share: trace backend,
// material dispatch, device, node library, shader cache folder, shared primary ray, and
// the material cache's options (cache_arguments.h). Each command keeps its own help text.
#pragma once

#include <stdexcept>
#include <string>

#include "cache_arguments.h"
#include "cli_common.h"
#include "runtime/renderer.h"

namespace memograph::cli {

struct RendererArguments {
  CacheArguments cache;
  std::string backend = "auto", materialDispatch = "auto", device = "-1", nodes, shaderCache;
  bool sharedPrimary = false;

  void registerWith(ArgumentScanner& scanner) {
    cache.registerWith(scanner);
    scanner.option("--backend", &backend);
    scanner.option("--material-dispatch", &materialDispatch);
    scanner.option("--device", &device);
    scanner.option("--nodes", &nodes);
    scanner.option("--shader-cache", &shaderCache);
    scanner.flag("--shared-primary", &sharedPrimary);
  }

  // The renderer's options (the command adds its own, e.g. validation). Throws
  // std::invalid_argument with a message for the user.
  runtime::RendererOptions parse() const {
    runtime::RendererOptions options;
    options.context.backend = runtime::parseBackend(backend);
    options.materialDispatch = runtime::parseMaterialDispatch(materialDispatch);
    options.cache = cache.parse();
    options.floorMaterials = cache.floorMaterials;
    std::uint32_t deviceIndex = 0;
    if (device != "-1" && !parseNumber(device, deviceIndex))
      throw std::invalid_argument(
          "--device takes a device index (memograph render "
          "--list-devices lists them), not '" +
          device + "'");
    options.context.deviceIndex = device == "-1" ? -1 : int(deviceIndex);
    options.shaderCacheDirectory = shaderCache;
    options.nodeLibraryDirectory = nodes;
    return options;
  }
};

}  // namespace memograph::cli
