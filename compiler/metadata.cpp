#include "compiler/metadata.h"

#include <algorithm>
#include <cstdio>

#include "compiler/literal.h"
#include "compiler/material_interface.h"

namespace memograph::compiler {

namespace {

// Orders names as MaterialInputs/MaterialOutputs declare them, so lists read naturally.
template <std::size_t N>
void sortByDeclaration(std::vector<std::string>& names,
                       const std::array<std::string_view, N>& order) {
  std::sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
    return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
  });
}

void addUnique(std::vector<std::string>& list, const std::string& item) {
  if (std::find(list.begin(), list.end(), item) == list.end())
    list.push_back(item);
}

std::string jsonString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escape[8];
          std::snprintf(escape, sizeof escape, "\\u%04x", c);
          out += escape;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string jsonList(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i ? ", " : "") + jsonString(items[i]);
  return out + "]";
}

// Whether a lobe sink (@output lobes) is given a normal of its own: its Normal or
// ClearcoatNormal socket (nodes/bsdf.inc) linked, or set to a constant other than (0, 0, 0),
// which means the material's normal. Such a material writes `lobeNormals`: the runtime then
// compiles the per-lobe frames (MG_LOBE_NORMALS) and the texel cache stores them.
bool writesLobeNormal(const ResolvedNode& node) {
  const NodeType& type = *node.type;
  if (std::find(type.outputsWritten.begin(), type.outputsWritten.end(), "lobes") ==
      type.outputsWritten.end())
    return false;
  for (std::size_t socket = 0; socket < type.sockets.size(); ++socket) {
    const std::string& name = type.sockets[socket].name;
    if (type.sockets[socket].direction != Direction::In ||
        (name != "Normal" && name != "ClearcoatNormal") || !node.inputs[socket])
      continue;
    const InputSource& source = *node.inputs[socket];
    if (source.kind == InputSource::Kind::Link)
      return true;
    if (source.kind == InputSource::Kind::Constant &&
        std::any_of(source.constant.components.begin(), source.constant.components.end(),
                    [](double c) { return c != 0.0; }))
      return true;
  }
  return false;
}

// Whether an opacity sink (@output opacity: OpacityOutput's In, PrincipledOutput's Alpha) may
// write an opacity below 1: its socket linked, or a constant below 1 (the sinks saturate it).
// A sink of another shape counts as maybe below 1, so that no opacity is ever ignored.
bool writesOpacityBelowOne(const ResolvedNode& node) {
  const NodeType& type = *node.type;
  if (std::find(type.outputsWritten.begin(), type.outputsWritten.end(), "opacity") ==
      type.outputsWritten.end())
    return false;
  for (std::size_t socket = 0; socket < type.sockets.size(); ++socket) {
    const std::string& name = type.sockets[socket].name;
    if (type.sockets[socket].direction != Direction::In || (name != "Alpha" && name != "In"))
      continue;
    if (!node.inputs[socket])
      return true;
    const InputSource& source = *node.inputs[socket];
    if (source.kind == InputSource::Kind::Link)
      return true;
    return std::any_of(source.constant.components.begin(), source.constant.components.end(),
                       [](double c) { return c < 1.0; });
  }
  return true;
}

}  // namespace

std::string formatShare(double share) {
  // Three decimals: the estimate is no finer, and a fixed format keeps the file stable.
  char text[16];
  std::snprintf(text, sizeof text, "%.3f", share);
  return text;
}

MaterialMetadata collectMetadata(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                                 const OverloadChoice& chosen, const MaterialCut& cut) {
  MaterialMetadata meta;
  meta.name = graph.name;
  meta.textures = graph.textures;
  meta.nodeCount = order.size();
  for (const std::size_t node : order) {
    const auto& type = *graph.nodes[node].type;
    for (const auto& input : type.inputsRead)
      addUnique(meta.inputsUsed, input);
    for (const auto& output : type.outputsWritten)
      addUnique(meta.outputsWritten, output);
    if (writesLobeNormal(graph.nodes[node]))
      addUnique(meta.outputsWritten, "lobeNormals");
    if (writesOpacityBelowOne(graph.nodes[node]))
      meta.opacityBelowOne = true;
    const auto& overload = type.overloads[*chosen[node]];
    if (overload.derivativeInputs + overload.derivativeOutputs > 0)
      meta.needsDerivatives = true;
  }
  sortByDeclaration(meta.inputsUsed, kMaterialInputNames);
  sortByDeclaration(meta.outputsWritten, kMaterialOutputNames);
  // Thesis §4.2: a cache keyed by (material, uv, mip) is only correct when nothing but the
  // texture coordinates varies across the surface.
  meta.cacheable = std::all_of(meta.inputsUsed.begin(), meta.inputsUsed.end(),
                               [](const std::string& input) { return input == "uv"; });
  meta.estimatedCost = cut.totalCost;
  if (!cut.empty()) {
    meta.cutDomain = std::string(variationName(cut.domain));
    meta.cutWidth = cut.width;
    meta.cutCostShare = cut.cachedShare();
  }
  return meta;
}

std::string metadataToJson(const MaterialMetadata& meta) {
  std::string out = "{\n";
  out += "  \"name\": " + jsonString(meta.name) + ",\n";
  out += "  \"cacheable\": " + std::string(meta.cacheable ? "true" : "false") + ",\n";
  out += "  \"needsDerivatives\": " + std::string(meta.needsDerivatives ? "true" : "false") + ",\n";
  out += "  \"nodeCount\": " + std::to_string(meta.nodeCount) + ",\n";
  out += "  \"inputs\": " + jsonList(meta.inputsUsed) + ",\n";
  out += "  \"outputs\": " + jsonList(meta.outputsWritten) + ",\n";
  out += "  \"textures\": " + jsonList(meta.textures) + ",\n";
  out += "  \"cutDomain\": " + jsonString(meta.cutDomain) + ",\n";
  out += "  \"cutWidth\": " + std::to_string(meta.cutWidth) + ",\n";
  out += "  \"cutCostShare\": " + formatShare(meta.cutCostShare);
  // Only for graphs with the traced input, so every other material's file stays as it was.
  if (const auto& ao = meta.ambientOcclusion) {
    out += ",\n  \"ambientOcclusion\": {\"distance\": " + formatFloat(ao->distance) +
           ", \"samples\": " + std::to_string(ao->samples) +
           ", \"inside\": " + (ao->inside ? "true" : "false") +
           ", \"onlyLocal\": " + (ao->onlyLocal ? "true" : "false") + "}";
  }
  if (const auto& bevel = meta.bevel) {
    out += ",\n  \"bevel\": {\"radius\": " + formatFloat(bevel->radius) +
           ", \"samples\": " + std::to_string(bevel->samples) + "}";
  }
  out += "\n";
  return out + "}\n";
}

}  // namespace memograph::compiler
