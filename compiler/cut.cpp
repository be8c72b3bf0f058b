#include "compiler/cut.h"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace memograph::compiler {

namespace {

// Cost per node name, in units of one arithmetic node (Add: 1, the default). `perOctave`
// applies per fBm octave of the node's Detail socket (Cycles: floor(Detail) + 1 octaves, one
// more blended in when Detail has a fraction). The rows that the committed GPU timing table
// tools/bench/node_timings_h100.txt covers are set from it by `tools/bench/node_cost_graphs.py
// calibrate --write` (tools/bench/node_costs_device.sh times each node as a dependent chain
// against a baseline: docs/design/memoization.md, "Measuring the node costs"); a node that
// timed at the noise of its measurement (folded into the chain by the driver) gets 0.5. The
// rows it cannot time (the inputs, outputs and BSDF sinks, Bump) are operation counts of
// nodes/*.inc. A chain waits for each image lookup's latency, which a real graph overlaps with
// other work: the image rows are upper bounds. Trust a share as a ranking of a cut's parts,
// not as a prediction of its time.
struct NodeCost {
  std::string_view node;
  double base = 0;
  double perOctave = 0;
};

const NodeCost kNodeCosts[] = {
    // Reading MaterialInputs and constants costs next to nothing.
    {"UVInput", 0},
    {"PositionInput", 0},
    {"NormalInput", 0},
    {"TangentInput", 0},
    {"VertexColorInput", 0},
    {"ViewInput", 0},
    {"BackfacingInput", 0},
    {"TimeInput", 0},
    {"TextureCoordinate", 0},
    {"UVMap", 0},
    {"Geometry", 1},
    {"Attribute", 0},
    {"ObjectInfo", 0},
    {"LightPath", 1},  // comparisons of the path state
    {"Float1Constant", 0},
    {"Float2Constant", 0},
    {"Float3Constant", 0},
    {"Float4Constant", 0},
    {"ColorConstant", 0},
    {"IntConstant", 0},
    // Output nodes store a field.
    {"BaseColorOutput", 0},
    {"ColorOutput", 0},
    {"MetallicOutput", 0},
    {"RoughnessOutput", 0},
    {"NormalOutput", 0},
    {"EmissionOutput", 0},
    {"OpacityOutput", 0},
    {"SpecularOutput", 0},
    {"SpecularTintOutput", 0},
    {"CyclesPrincipledOutput", 0},
    {"PrincipledOutput", 1},
    // BSDF sinks append a lobe (a colour times a weight); Mix Shader splits a weight.
    {"DiffuseBsdf", 1},
    {"GlossyBsdf", 1},
    {"VelvetBsdf", 1},
    {"RefractionBsdf", 1},
    {"GlassBsdf", 1},
    {"TransparentBsdf", 1},
    {"TranslucentBsdf", 1},
    // Three lobes, the sheen colour from the base colour's hue.
    {"PrincipledLayers", 2},
    {"MixShader", 1},
    // A hash and a comparison; the Principled BSDF's outputs and up to four lobes.
    {"ChooseShader", 3},
    {"PrincipledBsdf", 3},
    // Traced inputs: the tracer casts their rays before the graph runs, outside its cost
    // (and never in a cut); in the graph Ambient Occlusion scales a colour, Bevel reads.
    {"AmbientOcclusion", 0.5},
    {"Bevel", 0},
    // Procedural textures: a 3D Perlin octave is 8 gradient hashes and a trilinear blend.
    {"NoiseTexture", 0.5, 276.8},
    {"MusgraveTexture", 0.5, 272.8},
    {"WaveTexture", 0.5, 273.3},
    {"SimplexNoiseTexture", 0.5, 204.5},
    {"ValueNoiseTexture", 0.5, 138.4},
    {"VoronoiTexture", 2382.9},  // 27 cells (3D), each a hash and a distance
    {"WhiteNoiseTexture", 21.7},
    {"MagicTexture", 42.8},
    {"BrickTexture", 33},
    {"CheckerTexture", 15.4},
    {"CheckerTextureFiltered", 238.7},
    {"GradientTexture", 0.7},
    // A filtered fetch with explicit gradients; more when it misses the texture cache.
    {"ImageTexture", 537.7},
    // Cycles' filters over the full-resolution texels: 1, 4 and 16 fetches with their
    // weights; Box is three Linear lookups blended by the normal.
    {"ImageTextureClosest", 256.5},
    {"ImageTextureBilinear", 1081.8},
    {"ImageTextureBicubic", 4259.1},
    {"ImageTextureBox", 4185.2},
    {"ImageProjection", 99.7},  // an atan2 and an acos
    {"BrightnessContrast", 5.7},
    {"Gamma", 32.2},
    {"Invert", 3.5},
    {"LinearToSRGB", 34.9},
    {"SRGBToLinear", 37.4},
    {"MixColor", 5.9},  // one blend type (a constant): a lerp for Mix; the HSV ones cost more
    {"ColorRamp", 46.2},
    {"ColorRamp4", 0.5},
    {"FloatCurve", 1.8},
    {"RGBCurves", 296.3},
    {"VectorCurves", 166},
    {"HueSaturationValue", 62.4},
    {"Blackbody", 34.1},
    {"Wavelength", 149.6},
    {"Mapping", 8.9},
    {"VectorRotate", 9.8},
    {"VectorTransform", 0.5},
    {"Tangent", 2},
    {"Fresnel", 18.4},
    {"LayerWeight", 18.4},
    {"Bump", 12},
    {"NormalMap", 17},
    {"NormalFromPosition", 4},
    {"Normal", 7.9},
};

// fBm octaves for a Detail input: its constant, or Blender's default of 2 when it is linked.
double octaves(const ResolvedNode& node) {
  const int socket = node.type->socketIndex("Detail");
  double detail = 2.0;
  if (socket >= 0) {
    const auto& input = node.inputs[static_cast<std::size_t>(socket)];
    if (input && input->kind != InputSource::Kind::Link && input->constant.components.size() == 1)
      detail = input->constant.components[0];
  }
  detail = std::clamp(detail, 0.0, 15.0);
  return std::floor(detail) + 1.0 + (detail > std::floor(detail) ? 1.0 : 0.0);
}

bool isLinked(const std::optional<InputSource>& input) {
  return input && input->kind == InputSource::Kind::Link;
}

bool isSource(const ResolvedNode& node) {
  return std::none_of(node.inputs.begin(), node.inputs.end(),
                      [](const auto& input) { return isLinked(input); });
}

bool scheduled(const OverloadChoice& chosen, std::size_t node) {
  return node < chosen.size() && chosen[node].has_value();
}

}  // namespace

std::size_t keySpaceAxes(Variation domain) {
  return domain == Variation::Uv ? 2 : 3;
}

std::vector<std::string_view> nodesWithCostEstimates() {
  std::vector<std::string_view> names;
  for (const auto& entry : kNodeCosts)
    names.push_back(entry.node);
  return names;
}

double estimatedNodeCost(const ResolvedNode& node) {
  for (const auto& entry : kNodeCosts) {
    if (entry.node == node.type->name)
      return entry.base + (entry.perOctave > 0 ? entry.perOctave * octaves(node) : 0.0);
  }
  return 1.0;
}

namespace {

// A node's estimated cost as the graph runs it: an overload whose outputs carry derivatives
// evaluates its value and its change along both footprint axes (a noise node evaluates its
// fBm at the point and at the two offset points, as Cycles' Bump does; dual-number arithmetic
// carries three values), so it costs about three times the plain overload.
double scheduledNodeCost(const ResolvedGraph& graph, const OverloadChoice& chosen,
                         std::size_t node) {
  const auto& resolved = graph.nodes[node];
  double cost = estimatedNodeCost(resolved);
  if (!scheduled(chosen, node))
    return cost;
  const auto& types = resolved.type->overloads[*chosen[node]].socketTypes;
  for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
    if (resolved.type->sockets[s].direction != Direction::In && types[s].derivatives)
      return 3.0 * cost;
  }
  return cost;
}

}  // namespace

MaterialCut cutForDomain(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                         const OverloadChoice& chosen, const SocketVariation& variation,
                         Variation domain) {
  const std::size_t count = graph.nodes.size();
  auto outputType = [&](std::size_t node, std::size_t socket) {
    return graph.nodes[node].type->overloads[*chosen[node]].socketTypes[socket];
  };
  auto inDomain = [&](std::size_t node, std::size_t socket) {
    const Variation v = variation[node][socket];
    return v == Variation::Constant || v == domain;
  };
  // Nodes pushed out of the part because a value of theirs cannot cross the cut.
  std::vector<char> excluded(count, 0);
  std::vector<char> available(count, 0);  // the node may run in the part
  std::vector<char> inPart(count, 0);     // and none of its outputs leaves the domain
  std::vector<std::vector<char>> crossing(count);
  for (;;) {
    for (const std::size_t node : order) {
      const auto& resolved = graph.nodes[node];
      bool ok = !excluded[node] && !resolved.type->isSink;
      bool allOutputsInDomain = true;
      for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
        if (resolved.type->sockets[s].direction == Direction::In) {
          if (isLinked(resolved.inputs[s])) {
            const auto& input = *resolved.inputs[s];
            ok = ok && available[input.producer] && inDomain(input.producer, input.producerSocket);
          }
        } else {
          allOutputsInDomain = allOutputsInDomain && inDomain(node, s);
        }
      }
      available[node] = ok;
      inPart[node] = ok && allOutputsInDomain;
    }
    bool changed = false;
    for (const std::size_t node : order) {
      const auto& resolved = graph.nodes[node];
      crossing[node].assign(resolved.type->sockets.size(), 0);
      if (!available[node])
        continue;
      for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
        if (resolved.type->sockets[s].direction == Direction::In || variation[node][s] != domain)
          continue;
        const bool leaves = std::any_of(
            resolved.consumers[s].begin(), resolved.consumers[s].end(),
            [&](const Consumer& c) { return scheduled(chosen, c.node) && !inPart[c.node]; });
        if (!leaves)
          continue;
        const Type type = outputType(node, s);
        // A source node (it reads only MaterialInputs) runs in both functions instead of
        // handing over a value it cannot (no floats) or a gradient that costs more floats than
        // reading the inputs again: it costs less than anything a cut could save, and its
        // other readers stay in the part.
        if ((type.derivatives || type.width() == 0) && isSource(resolved))
          continue;
        if (type.width() == 0) {
          excluded[node] = 1;
          changed = true;
        }
        crossing[node][s] = 1;
      }
    }
    if (!changed)
      break;
  }

  // The rest: from the output nodes back, stopping at values the cut provides.
  std::vector<char> inRest(count, 0);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const std::size_t node = *it;
    const auto& resolved = graph.nodes[node];
    if (resolved.type->isSink)
      inRest[node] = 1;
    if (!inRest[node])
      continue;
    for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
      if (resolved.type->sockets[s].direction == Direction::Out || !isLinked(resolved.inputs[s]))
        continue;
      const auto& input = *resolved.inputs[s];
      if (!crossing[input.producer][input.producerSocket])
        inRest[input.producer] = 1;
    }
  }

  MaterialCut cut;
  cut.domain = domain;
  std::vector<char> inCut(count, 0);
  for (const std::size_t node : order) {
    cut.totalCost += scheduledNodeCost(graph, chosen, node);
    // A source node the rest runs anyway gives its values there; caching them saves nothing.
    if (inRest[node])
      continue;
    for (std::size_t s = 0; s < crossing[node].size(); ++s) {
      if (!crossing[node][s])
        continue;
      CutValue value{node, s, outputType(node, s), cut.width};
      value.gradientAxes = value.type.derivatives ? keySpaceAxes(domain) : 0;
      cut.values.push_back(value);
      cut.width += value.width();
      inCut[node] = 1;
    }
  }
  // The cut function runs what the values need.
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const std::size_t node = *it;
    if (!inCut[node])
      continue;
    const auto& resolved = graph.nodes[node];
    for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
      if (resolved.type->sockets[s].direction != Direction::Out && isLinked(resolved.inputs[s]))
        inCut[resolved.inputs[s]->producer] = 1;
    }
  }
  for (const std::size_t node : order) {
    if (inCut[node]) {
      cut.cutNodes.push_back(node);
      if (!inRest[node])
        cut.cachedCost += scheduledNodeCost(graph, chosen, node);
    }
    if (inRest[node])
      cut.restNodes.push_back(node);
  }
  if (cut.cachedCost <= 0) {
    MaterialCut none;
    none.totalCost = cut.totalCost;
    none.restNodes = order;
    return none;
  }
  return cut;
}

MaterialCut findCut(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                    const OverloadChoice& chosen) {
  const SocketVariation variation = analyseVariation(graph, order);
  MaterialCut best = cutForDomain(graph, order, chosen, variation, Variation::Uv);
  for (const Variation domain : {Variation::Object, Variation::World}) {
    MaterialCut candidate = cutForDomain(graph, order, chosen, variation, domain);
    if (candidate.empty())
      continue;
    if (best.empty() || candidate.cachedCost > best.cachedCost ||
        (candidate.cachedCost == best.cachedCost && candidate.width < best.width))
      best = std::move(candidate);
  }
  return best;
}

}  // namespace memograph::compiler
