#include "compiler/traced_inputs.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace memograph::compiler {

namespace {

// The constant (or default) a setting socket holds; reports and returns nothing when it is
// linked, absent, or not a number.
std::optional<double> settingValue(const ResolvedNode& node, std::string_view socket,
                                   const SourceFile& file, Diagnostics& diagnostics) {
  const NodeType& type = *node.type;
  const int index = type.socketIndex(socket);
  if (index < 0 || !node.inputs[std::size_t(index)]) {
    diagnostics.error(file, node.source->location,
                      type.name + " has no input '" + std::string(socket) +
                          "': the tracer needs it to trace the node's rays");
    return std::nullopt;
  }
  const InputSource& input = *node.inputs[std::size_t(index)];
  if (input.kind == InputSource::Kind::Link) {
    diagnostics.error(file, input.location,
                      type.name + "." + std::string(socket) +
                          " must be a constant: the path tracer traces the node's rays before "
                          "the graph runs, with settings it reads from the material's metadata");
    return std::nullopt;
  }
  if (input.constant.kind != Literal::Kind::Number || input.constant.components.size() != 1) {
    diagnostics.error(file, input.location,
                      type.name + "." + std::string(socket) + " takes a number");
    return std::nullopt;
  }
  return input.constant.components[0];
}

bool reads(const NodeType& type, std::string_view input) {
  return std::find(type.inputsRead.begin(), type.inputsRead.end(), input) != type.inputsRead.end();
}

// Samples as Blender bounds them: a whole number 1..128. Reports and returns false otherwise.
bool checkSamples(const ResolvedNode& node, double samples, const SourceFile& file,
                  Diagnostics& diagnostics) {
  if (samples >= 1.0 && samples <= 128.0 && std::floor(samples) == samples)
    return true;
  diagnostics.error(file, node.source->location,
                    node.type->name + ".Samples must be a whole number from 1 to 128");
  return false;
}

// A distance as Blender bounds it: finite, >= 0. Reports and returns false otherwise.
bool checkDistance(const ResolvedNode& node, std::string_view socket, double value,
                   const SourceFile& file, Diagnostics& diagnostics) {
  if (std::isfinite(value) && value >= 0.0)
    return true;
  diagnostics.error(
      file, node.source->location,
      node.type->name + "." + std::string(socket) + " must be a finite distance >= 0");
  return false;
}

// The one value per hit the tracer fills: every node reading it must share the settings.
template <class Settings>
bool agrees(const std::optional<Settings>& found, const Settings& settings,
            const ResolvedNode& node, const SourceFile& file, Diagnostics& diagnostics) {
  if (!found || *found == settings)
    return true;
  diagnostics.error(file, node.source->location,
                    "two " + node.type->name +
                        " nodes with different settings: the path tracer fills one value per "
                        "hit for them, so a material's " +
                        node.type->name + " nodes must share their settings");
  return false;
}

}  // namespace

std::optional<AmbientOcclusionSettings> collectAmbientOcclusionSettings(
    const ResolvedGraph& graph, const std::vector<std::size_t>& order, const SourceFile& file,
    Diagnostics& diagnostics) {
  std::optional<AmbientOcclusionSettings> found;
  for (const std::size_t index : order) {
    const ResolvedNode& node = graph.nodes[index];
    if (!reads(*node.type, kAmbientOcclusionInput))
      continue;
    const auto distance = settingValue(node, "Distance", file, diagnostics);
    const auto samples = settingValue(node, "Samples", file, diagnostics);
    const auto inside = settingValue(node, "Inside", file, diagnostics);
    const auto onlyLocal = settingValue(node, "OnlyLocal", file, diagnostics);
    if (!distance || !samples || !inside || !onlyLocal ||
        !checkDistance(node, "Distance", *distance, file, diagnostics) ||
        !checkSamples(node, *samples, file, diagnostics))
      return std::nullopt;
    AmbientOcclusionSettings settings;
    settings.distance = *distance;
    settings.samples = static_cast<std::uint32_t>(*samples);
    settings.inside = *inside != 0.0;
    settings.onlyLocal = *onlyLocal != 0.0;
    if (!agrees(found, settings, node, file, diagnostics))
      return std::nullopt;
    found = settings;
  }
  return found;
}

std::optional<BevelSettings> collectBevelSettings(const ResolvedGraph& graph,
                                                  const std::vector<std::size_t>& order,
                                                  const SourceFile& file,
                                                  Diagnostics& diagnostics) {
  std::optional<BevelSettings> found;
  for (const std::size_t index : order) {
    const ResolvedNode& node = graph.nodes[index];
    if (!reads(*node.type, kBevelInput))
      continue;
    const auto radius = settingValue(node, "Radius", file, diagnostics);
    const auto samples = settingValue(node, "Samples", file, diagnostics);
    if (!radius || !samples || !checkDistance(node, "Radius", *radius, file, diagnostics) ||
        !checkSamples(node, *samples, file, diagnostics))
      return std::nullopt;
    BevelSettings settings;
    settings.radius = *radius;
    settings.samples = static_cast<std::uint32_t>(*samples);
    if (!agrees(found, settings, node, file, diagnostics))
      return std::nullopt;
    found = settings;
  }
  return found;
}

}  // namespace memograph::compiler
