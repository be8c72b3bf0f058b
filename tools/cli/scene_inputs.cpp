// The environment image and scene packs for render, bench and pack (scene_inputs.h).
#include "scene_inputs.h"

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include <cmath>
#include <iostream>
#include <memory>

#include "cli_common.h"
#include "runtime/scene/pack/scene_pack.h"
#ifdef MEMOGRAPH_HAVE_IO
#include "tools/io/image_io.h"
#endif

namespace memograph::cli {

int loadEnvironmentImage([[maybe_unused]] std::string_view command, std::string environment,
                         runtime::Scene& scene) {
  // Unused in builds without the io module, which read no environment image.
  [[maybe_unused]] float strength = 1.0f, uOffset = 0.0f;
  if (environment.empty() && !scene.environment.imagePath.empty() &&
      scene.environment.imageRgb.empty()) {
    environment = scene.environment.imagePath;
    strength = scene.environment.imageStrength;
    uOffset = scene.environment.imageUOffset;
  }
  if (environment.empty())
    return kExitOk;
#ifdef MEMOGRAPH_HAVE_IO
  compiler::Diagnostics diagnostics;
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
                    shift = std::size_t(std::lround(uOffset * float(w))) % (w ? w : 1);
  for (std::size_t y = 0; y < std::size_t(image->height); ++y) {
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t i = 4 * (y * w + (x + shift) % w);
      env.imageRgb.insert(env.imageRgb.end(),
                          {strength * image->rgba[i], strength * image->rgba[i + 1],
                           strength * image->rgba[i + 2]});
    }
  }
  return kExitOk;
#else
  std::cerr << "memograph " << command << ": this build reads no images (no OpenImageIO)\n";
  return kExitFailure;
#endif
}

int loadScenePackFile(std::string_view command, const std::string& path,
                      TraceCommandOptions& options, runtime::Scene& scene,
                      std::vector<runtime::Camera>& cameraPath) {
  std::string error;
  auto pack = runtime::readScenePack(path, error);
  if (!pack) {
    std::cerr << "memograph " << command << ": " << error << "\n";
    return kExitFailure;
  }
  if (!options.materials.empty())
    std::cerr << "memograph " << command << ": --materials is ignored: scene pack " << path
              << " holds its own graphs\n";
  scene = std::move(pack->scene);
  cameraPath = std::move(pack->cameraPath);
  auto textures =
      std::make_shared<const std::vector<runtime::PackedTexture>>(std::move(pack->textures));
  options.renderer.textureLoader = [textures](const std::string& name) {
    return runtime::packedTexture(*textures, name);
  };
  return kExitOk;
}

}  // namespace memograph::cli
#endif
