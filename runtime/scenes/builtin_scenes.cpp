#include "runtime/scenes/builtin_scenes.h"

#include <stdexcept>

namespace memograph::runtime {

std::vector<std::string> builtinSceneNames() {
  return {"classroom", "landscape"};
}

Scene makeBuiltinScene(std::string_view name, const BuiltinSceneOptions& options) {
  if (options.terrainCells < 2 || options.terrainCells > 4096) {
    throw std::invalid_argument("built-in scene: terrainCells must be in 2..4096, got " +
                                std::to_string(options.terrainCells));
  }
  if (options.materialCost.octaves < 1 || options.materialCost.octaves > 16 ||
      options.materialCost.layers < 0 || options.materialCost.layers > 16) {
    throw std::invalid_argument(
        "built-in scene: material octaves must be in 1..16 and layers in 0..16, got " +
        std::to_string(options.materialCost.octaves) + " and " +
        std::to_string(options.materialCost.layers));
  }
  if (name == "classroom")
    return makeClassroomScene(options);
  if (name == "landscape")
    return makeLandscapeScene(options);
  std::string known;
  for (const std::string& n : builtinSceneNames())
    known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown built-in scene '" + std::string(name) +
                              "'; known scenes: " + known);
}

}  // namespace memograph::runtime
