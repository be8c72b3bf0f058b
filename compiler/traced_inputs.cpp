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

bool readsAmbientOcclusion(const NodeType& type) {
  return std::find(type.inputsRead.begin(), type.inputsRead.end(), kAmbientOcclusionInput) !=
         type.inputsRead.end();
}

}  // namespace

std::optional<AmbientOcclusionSettings> collectAmbientOcclusionSettings(
    const ResolvedGraph& graph, const std::vector<std::size_t>& order, const SourceFile& file,
    Diagnostics& diagnostics) {
  std::optional<AmbientOcclusionSettings> found;
  for (const std::size_t index : order) {
    const ResolvedNode& node = graph.nodes[index];
    if (!readsAmbientOcclusion(*node.type))
      continue;
    const auto distance = settingValue(node, "Distance", file, diagnostics);
    const auto samples = settingValue(node, "Samples", file, diagnostics);
    const auto inside = settingValue(node, "Inside", file, diagnostics);
    const auto onlyLocal = settingValue(node, "OnlyLocal", file, diagnostics);
    if (!distance || !samples || !inside || !onlyLocal)
      return std::nullopt;
    // Blender's ranges: Distance 0..1000 (the socket's soft range; larger is allowed here),
    // Samples 1..128.
    if (!std::isfinite(*distance) || *distance < 0.0) {
      diagnostics.error(file, node.source->location,
                        node.type->name + ".Distance must be a finite distance >= 0");
      return std::nullopt;
    }
    if (!(*samples >= 1.0 && *samples <= 128.0) || std::floor(*samples) != *samples) {
      diagnostics.error(file, node.source->location,
                        node.type->name + ".Samples must be a whole number from 1 to 128");
      return std::nullopt;
    }
    AmbientOcclusionSettings settings;
    settings.distance = *distance;
    settings.samples = static_cast<std::uint32_t>(*samples);
    settings.inside = *inside != 0.0;
    settings.onlyLocal = *onlyLocal != 0.0;
    if (found && !(*found == settings)) {
      diagnostics.error(file, node.source->location,
                        "two " + node.type->name +
                            " nodes with different settings: the path tracer fills one "
                            "ambient-occlusion value per hit, so a material's AO nodes must "
                            "share Distance, Samples, Inside and Only Local");
      return std::nullopt;
    }
    found = settings;
  }
  return found;
}

}  // namespace memograph::compiler
