#include "runtime/scene/builtin/builtin_scenes.h"

#include <charconv>
#include <stdexcept>

namespace memograph::runtime {

std::vector<std::string> builtinSceneNames() {
  return {"classroom", "landscape", "city"};
}

std::optional<BuiltinSceneSpec> parseBuiltinSceneSpec(std::string_view text, std::string& error) {
  BuiltinSceneSpec spec;
  const std::size_t colon = text.find(':');
  spec.name = std::string(text.substr(0, colon));
  if (spec.name.empty()) {
    error = "no built-in scene name before ':'";
    return std::nullopt;
  }
  if (colon == std::string_view::npos)
    return spec;
  std::string_view rest = text.substr(colon + 1);
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    const std::size_t equals = item.find('=');
    const std::string_view key = item.substr(0, equals);
    const std::string_view value =
        equals == std::string_view::npos ? std::string_view{} : item.substr(equals + 1);
    if (key == "scale") {
      double scale = 0.0;
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), scale);
      if (value.empty() || ec != std::errc() || end != value.data() + value.size() ||
          !(scale > 0.0 && scale <= 1.0)) {
        error = "bad option '" + std::string(item) + "' for built-in scene '" + spec.name +
                "': scale is a number in (0, 1], e.g. scale=0.02";
        return std::nullopt;
      }
      spec.options.cityScale = scale;
      continue;
    }
    if (key == "path") {
      if (value == "street") {
        spec.options.cityPath = CityCameraPath::Street;
      } else if (value == "aerial") {
        spec.options.cityPath = CityCameraPath::Aerial;
      } else {
        error = "bad option '" + std::string(item) + "' for built-in scene '" + spec.name +
                "': path is street (the default: low through the streets) or aerial (in from "
                "high above the city)";
        return std::nullopt;
      }
      continue;
    }
    int number = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), number);
    if (equals == std::string_view::npos || value.empty() || ec != std::errc() ||
        end != value.data() + value.size()) {
      error = "bad option '" + std::string(item) + "' for built-in scene '" + spec.name +
              "': expected KEY=INTEGER";
      return std::nullopt;
    }
    if (key == "octaves") {
      spec.options.materialCost.octaves = number;
    } else if (key == "layers") {
      spec.options.materialCost.layers = number;
    } else if (key == "terrain") {
      spec.options.terrainCells = number;
    } else if (key == "nee") {
      if (number != 0 && number != 1) {
        error = "bad option '" + std::string(item) + "' for built-in scene '" + spec.name +
                "': nee is 0 (no light sampling of emissive triangles) or 1";
        return std::nullopt;
      }
      spec.options.emissiveNee = number == 1;
    } else {
      error = "unknown option '" + std::string(key) + "' for built-in scene '" + spec.name +
              "'; known options: octaves, layers, terrain, nee, scale, path";
      return std::nullopt;
    }
  }
  return spec;
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
  if (name == "city")
    return makeCityScene(options);
  std::string known;
  for (const std::string& n : builtinSceneNames())
    known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown built-in scene '" + std::string(name) +
                              "'; known scenes: " + known);
}

}  // namespace memograph::runtime
