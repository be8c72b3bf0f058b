// What render, bench and pack read besides the scene itself: the environment image, and a
// scene pack with what it brings (its camera path, its textures).
#pragma once

// Only in builds with the renderer (MEMOGRAPH_HAVE_RUNTIME), whose scene types these use.
#ifdef MEMOGRAPH_HAVE_RUNTIME
#include <string>
#include <string_view>
#include <vector>

#include "option_table.h"
#include "runtime/scene/scene.h"

namespace memograph::cli {

// The environment image: `environment`, or the one the scene names (the Blender export's
// world), which `environment` replaces; loaded into scene.environment.imageRgb (strength and
// u offset applied). Nothing to do when neither names one or the image is loaded already.
// kExitFailure after printing "memograph <command>: ..." when it cannot be read (or the
// build reads no images).
int loadEnvironmentImage(std::string_view command, std::string environment, runtime::Scene& scene);

// Reads the scene pack `path` into `scene` and points `options` at it: its textures become
// the texture loader's, and its camera path `cameraPath` (empty when it has none). The
// --materials note says the pack's own graphs are used. kExitFailure after printing the
// reader's message (file and offset).
int loadScenePackFile(std::string_view command, const std::string& path,
                      TraceCommandOptions& options, runtime::Scene& scene,
                      std::vector<runtime::Camera>& cameraPath);

}  // namespace memograph::cli
#endif
