#include "compiler/variation.h"

#include <optional>
#include <string>

#include "compiler/material_interface.h"

namespace memograph::compiler {

namespace {

// Source nodes that read members of more than one class copy each member to its own output,
// so each output gets its member's class; the node's joined class would make, e.g., the
// Generated output of a Texture Coordinate node per-hit only because Reflection reads the
// view. Names follow nodes/blender_inputs.inc; variation_test checks them against the library.
const std::vector<SourceSocketClass> kSourceSocketClasses = {
    {"TextureCoordinate", "Generated", Variation::Object},
    {"TextureCoordinate", "Normal", Variation::PerHit},
    {"TextureCoordinate", "UV", Variation::Uv},
    {"TextureCoordinate", "Object", Variation::Object},
    {"TextureCoordinate", "Reflection", Variation::PerHit},
    {"Geometry", "Position", Variation::World},
    {"Geometry", "Normal", Variation::PerHit},
    // Cycles' radial tangent: from generated, made orthogonal to the shading normal.
    {"Geometry", "Tangent", Variation::PerHit},
    // The face normal flipped towards the ray.
    {"Geometry", "TrueNormal", Variation::PerHit},
    {"Geometry", "Incoming", Variation::PerHit},
    {"Geometry", "Backfacing", Variation::PerHit},
};

std::optional<Variation> tabulated(const NodeType& type, std::size_t socket) {
  for (const auto& entry : kSourceSocketClasses) {
    if (entry.node == type.name && entry.socket == type.sockets[socket].name)
      return entry.variation;
  }
  return std::nullopt;
}

}  // namespace

std::string_view variationName(Variation variation) {
  switch (variation) {
    case Variation::Constant:
      return "constant";
    case Variation::Uv:
      return "uv";
    case Variation::Object:
      return "object";
    case Variation::World:
      return "world";
    case Variation::PerHit:
      return "per-hit";
    case Variation::PerFrame:
      return "per-frame";
  }
  return "per-frame";
}

bool isKeyDomain(Variation variation) {
  return variation == Variation::Uv || variation == Variation::Object ||
         variation == Variation::World;
}

Variation join(Variation a, Variation b) {
  if (a == b)
    return a;
  if (a == Variation::Constant)
    return b;
  if (b == Variation::Constant)
    return a;
  if (a == Variation::PerFrame || b == Variation::PerFrame)
    return Variation::PerFrame;
  // Two different key domains, or a key domain and PerHit.
  return Variation::PerHit;
}

Variation inputVariation(std::string_view member) {
  if (member == "uv")
    return Variation::Uv;
  if (member == "generated" || member == "objectPosition" || member == "objectLocation" ||
      member == "objectRandom")
    return Variation::Object;
  if (member == "position")
    return Variation::World;
  if (member == "time")
    return Variation::PerFrame;
  if (member == "normal" || member == "tangent" || member == "vertexColor" || member == "view" ||
      member == "geometricNormal" || member == "objectNormal" || member == "backfacing")
    return Variation::PerHit;
  // The path state (Light Path) belongs to the ray, not to the surface: two rays reaching
  // one texel at different depths or by different lobes see different values, so no key
  // domain determines it and it never enters a cut.
  if (isPathInput(member))
    return Variation::PerHit;
  // Traced inputs (Ambient Occlusion) depend on the geometry around the hit, which no key
  // domain's texel or voxel determines (two hits of one texel see different occluders, and
  // each hit's value is a fresh Monte Carlo estimate): per hit, never in a cut.
  if (isTracedInput(member))
    return Variation::PerHit;
  return Variation::Constant;
}

SocketVariation analyseVariation(const ResolvedGraph& graph,
                                 const std::vector<std::size_t>& order) {
  SocketVariation result(graph.nodes.size());
  for (std::size_t node = 0; node < graph.nodes.size(); ++node)
    result[node].assign(graph.nodes[node].type->sockets.size(), Variation::Constant);
  for (const std::size_t node : order) {
    const auto& resolved = graph.nodes[node];
    const NodeType& type = *resolved.type;
    Variation joined = Variation::Constant;
    for (const auto& member : type.inputsRead)
      joined = join(joined, inputVariation(member));
    bool linked = false;
    for (std::size_t s = 0; s < type.sockets.size(); ++s) {
      const auto& input = resolved.inputs[s];
      if (type.sockets[s].direction == Direction::Out || !input ||
          input->kind != InputSource::Kind::Link)
        continue;
      linked = true;
      joined = join(joined, result[input->producer][input->producerSocket]);
    }
    for (std::size_t s = 0; s < type.sockets.size(); ++s) {
      if (type.sockets[s].direction == Direction::In)
        continue;
      const auto own = linked ? std::nullopt : tabulated(type, s);
      result[node][s] = own ? *own : joined;
    }
  }
  return result;
}

const std::vector<SourceSocketClass>& sourceSocketClasses() {
  return kSourceSocketClasses;
}

}  // namespace memograph::compiler
