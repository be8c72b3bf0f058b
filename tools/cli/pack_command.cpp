// memograph pack SCENE --materials DIR --out FILE.mgpack: imports a glTF/OBJ scene (assimp),
// reads its material graphs, environment image, camera path and textures (OpenImageIO) and
// writes them as one scene pack (runtime/scene/pack/), which builds without the io module
// (the GPU bundle) render and bench.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>

#include "cli_common.h"
#include "commands.h"

#if defined(MEMOGRAPH_HAVE_IO) && defined(MEMOGRAPH_HAVE_RUNTIME) && defined(MEMOGRAPH_HAVE_SCENES)
#include "runtime/materials/material_linker.h"
#include "runtime/scene/builtin/camera_path.h"
#include "runtime/scene/pack/scene_pack.h"
#include "scene_inputs.h"
#include "tools/io/image_io.h"
#include "tools/io/scene_import.h"
#define MEMOGRAPH_CAN_PACK 1
#endif

namespace memograph::cli {

#ifndef MEMOGRAPH_CAN_PACK
int runPack(std::span<const std::string_view>) {
  std::cerr << "memograph pack: this build cannot read scene files (no io module: assimp and "
               "OpenImageIO); write the pack with a full build and carry the .mgpack\n";
  return kExitFailure;
}
#else

namespace {

constexpr std::string_view kHelp =
    "usage: memograph pack SCENE --materials DIR --out FILE.mgpack [options]\n"
    "\n"
    "Imports a glTF/OBJ scene (SCENE, its material names mapped to DIR/<name>.mgraph as in\n"
    "'render') and writes it as one self-contained scene pack: meshes, instances, lights,\n"
    "camera, the world (its environment image decoded), every material graph as text and\n"
    "every texture the graphs sample, decoded. 'render' and 'bench' read a .mgpack in any\n"
    "build, also one without assimp and OpenImageIO (the GPU bundle). The same inputs give\n"
    "the same bytes. Format: docs/design/scene-pack.md.\n"
    "\n"
    "options:\n"
    "  --materials DIR     folder of the scene's .mgraph graphs (required)\n"
    "  --out FILE          the pack to write, ending in .mgpack (required); written whole or\n"
    "                      not at all\n"
    "  --camera-path FILE  a camera path (render --camera-path's format) stored in the pack;\n"
    "                      render and bench then follow it (default: none, the scene's camera)\n"
    "  --environment FILE  an equirectangular image stored as the world, replacing the one\n"
    "                      the scene names (default: the scene's)\n"
    "  --nodes DIR         node library folder used to find the graphs' textures (default:\n"
    "                      the embedded library)\n";

struct PackOptions {
  std::string materials, out, cameraPath, environment, nodes;
};

// The textures the scene's graphs sample, each under the name its graph gives it (what the
// renderer asks a pack for), decoded from the file that name resolves to beside its graph.
// Two graphs naming different files alike cannot share one pack: refused, naming both.
bool packTextures(const runtime::Scene& imported, const std::vector<runtime::MaterialRef>& asText,
                  const std::string& nodes, std::vector<runtime::PackedTexture>& textures) {
  runtime::MaterialLinkOptions linkOptions;
  linkOptions.nodeLibraryDirectory = nodes;
  std::vector<std::string> files, names;
  try {
    files = runtime::linkMaterials(imported.materials, linkOptions).texturePaths;
    names = runtime::linkMaterials(asText, linkOptions).texturePaths;
  } catch (const std::runtime_error& e) {
    std::cerr << "memograph pack: " << e.what() << "\n";
    return false;
  }
  std::map<std::string, std::string> fileByName;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto [at, added] = fileByName.emplace(names[i], files[i]);
    if (!added && at->second != files[i]) {
      std::cerr << "memograph pack: two graphs name texture '" << names[i]
                << "' for different files (" << at->second << ", " << files[i]
                << "); give them distinct names\n";
      return false;
    }
  }
  for (const auto& [name, file] : fileByName) {  // by name: the same pack, the same bytes
    compiler::Diagnostics diagnostics;
    auto image = io::readImageFloat(file, diagnostics);
    if (!image) {
      printDiagnostics(diagnostics);
      return false;
    }
    textures.push_back({name, std::move(*image)});
  }
  return true;
}

int writePack(const std::string& sceneFile, const PackOptions& options) {
  compiler::Diagnostics diagnostics;
  auto imported = io::importScene(sceneFile, options.materials, diagnostics);
  printDiagnostics(diagnostics);
  if (!imported)
    return kExitFailure;
  runtime::ScenePack pack;
  pack.scene = *imported;
  if (const int code = loadEnvironmentImage("pack", options.environment, pack.scene);
      code != kExitOk)
    return code;
  // The image is in the pack; its file's name alone is kept, for people reading the pack.
  pack.scene.environment.imagePath =
      std::filesystem::path(pack.scene.environment.imagePath).filename().string();
  if (!options.cameraPath.empty()) {
    compiler::Diagnostics pathDiagnostics;
    auto path = runtime::loadCameraPath(options.cameraPath, pathDiagnostics);
    printDiagnostics(pathDiagnostics);
    if (!path)
      return kExitFailure;
    pack.cameraPath = path->frames;
  }
  // Graphs travel as text; the name of the graph's file stays out of the pack, so that its
  // bytes do not depend on where the scene was imported.
  for (runtime::MaterialRef& material : pack.scene.materials) {
    if (material.graphText.empty()) {
      std::string error;
      const auto text = readFile(material.graphPath, error);
      if (!text) {
        std::cerr << "memograph pack: " << material.graphPath << ": " << error << "\n";
        return kExitFailure;
      }
      material.graphText = *text;
    }
    material.graphPath.clear();
  }
  if (!packTextures(*imported, pack.scene.materials, options.nodes, pack.textures))
    return kExitFailure;
  std::string error;
  if (!runtime::writeScenePack(options.out, pack, error)) {
    std::cerr << "memograph pack: " << error << "\n";
    return kExitFailure;
  }
  std::cerr << "memograph: wrote " << options.out << " (" << pack.scene.meshes.size() << " meshes, "
            << pack.scene.instances.size() << " instances, " << pack.scene.materials.size()
            << " materials, " << pack.textures.size() << " textures, " << pack.cameraPath.size()
            << " camera path frames)\n";
  return kExitOk;
}

}  // namespace

int runPack(std::span<const std::string_view> args) {
  PackOptions options;
  ArgumentScanner scanner("pack", args);
  scanner.option("--materials", &options.materials);
  scanner.option("--out", &options.out);
  scanner.option("--camera-path", &options.cameraPath);
  scanner.option("--environment", &options.environment);
  scanner.option("--nodes", &options.nodes);
  scanner.help(kHelp);
  std::vector<std::string> positional;
  if (const auto exitCode = scanner.scan(positional))
    return *exitCode;
  if (positional.size() != 1)
    return usageError("pack", "expected one scene file");
  if (options.materials.empty())
    return usageError("pack", "--materials DIR is required");
  if (options.out.empty())
    return usageError("pack", "--out FILE.mgpack is required");
  if (!runtime::isScenePackPath(options.out))
    return usageError("pack", "--out must name a .mgpack file, not '" + options.out + "'");
  std::vector<CommandFile> inputs = {{"SCENE", positional[0]},
                                     {"--camera-path", options.cameraPath},
                                     {"--environment", options.environment}};
  addFolderInputs(inputs, "--materials graph", options.materials, ".mgraph", false);
  if (const int code = refuseOutputOverInput("pack", {{"--out", options.out}}, inputs);
      code != kExitOk)
    return code;
  if (const int code = checkOutputFile("pack", options.out); code != kExitOk)
    return code;
  return writePack(positional[0], options);
}
#endif

}  // namespace memograph::cli
