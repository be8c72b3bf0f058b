#include "runtime/scene/builtin/builtin_scenes.h"

#include <charconv>
#include <stdexcept>
#include <tuple>

namespace memograph::runtime {

namespace {

std::string terrainRange() {
  return "terrain (the landscape's terrain grid: cells per side) is an integer in " +
         std::to_string(kMinTerrainCells) + ".." + std::to_string(kMaxTerrainCells) +
         ", e.g. terrain=256";
}
std::string octavesRange() {
  return "octaves (noise octaves of every generated material) is an integer in " +
         std::to_string(kMinOctaves) + ".." + std::to_string(kMaxOctaves);
}
std::string tracedSamplesRange(const char* key, const char* node) {
  return std::string(key) + " (the samples of an " + node +
         " node in every generated material; 0: none) is an integer in 0.." +
         std::to_string(kMaxTracedInputSamples);
}
std::string layersRange() {
  return "layers (extra layers of every generated material) is an integer in " +
         std::to_string(kMinLayers) + ".." + std::to_string(kMaxLayers);
}

}  // namespace

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
    // The integer options' ranges, checked here so the message names the option as written.
    const auto outOfRange = [&](const std::string& what) {
      error =
          "bad option '" + std::string(item) + "' for built-in scene '" + spec.name + "': " + what;
      return std::nullopt;
    };
    if (key == "octaves") {
      if (number < kMinOctaves || number > kMaxOctaves)
        return outOfRange(octavesRange());
      spec.options.materialCost.octaves = number;
    } else if (key == "layers") {
      if (number < kMinLayers || number > kMaxLayers)
        return outOfRange(layersRange());
      spec.options.materialCost.layers = number;
    } else if (key == "ao") {
      if (number < 0 || number > kMaxTracedInputSamples)
        return outOfRange(tracedSamplesRange("ao", "Ambient Occlusion"));
      spec.options.materialCost.ambientOcclusionSamples = number;
    } else if (key == "bevel") {
      if (number < 0 || number > kMaxTracedInputSamples)
        return outOfRange(tracedSamplesRange("bevel", "Bevel"));
      spec.options.materialCost.bevelSamples = number;
    } else if (key == "terrain") {
      if (number < kMinTerrainCells || number > kMaxTerrainCells)
        return outOfRange(terrainRange());
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
              "'; known options: octaves, layers, terrain, nee, scale, path, ao, bevel";
      return std::nullopt;
    }
  }
  return spec;
}

Scene makeBuiltinScene(std::string_view name, const BuiltinSceneOptions& options) {
  if (options.terrainCells < kMinTerrainCells || options.terrainCells > kMaxTerrainCells)
    throw std::invalid_argument("built-in scene option " + terrainRange() + ", got " +
                                std::to_string(options.terrainCells));
  if (options.materialCost.octaves < kMinOctaves || options.materialCost.octaves > kMaxOctaves)
    throw std::invalid_argument("built-in scene option " + octavesRange() + ", got " +
                                std::to_string(options.materialCost.octaves));
  if (options.materialCost.layers < kMinLayers || options.materialCost.layers > kMaxLayers)
    throw std::invalid_argument("built-in scene option " + layersRange() + ", got " +
                                std::to_string(options.materialCost.layers));
  for (const auto& [samples, key, node] :
       {std::tuple(options.materialCost.ambientOcclusionSamples, "ao", "Ambient Occlusion"),
        std::tuple(options.materialCost.bevelSamples, "bevel", "Bevel")})
    if (samples < 0 || samples > kMaxTracedInputSamples)
      throw std::invalid_argument("built-in scene option " + tracedSamplesRange(key, node) +
                                  ", got " + std::to_string(samples));
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
