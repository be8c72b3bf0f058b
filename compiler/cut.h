// The cut of a material graph: the largest part whose values one cache key determines, and
// the values that leave it (thesis §7, "applying memoization to well-suited subgraphs
// instead of the entire graph").
//
// For a key domain K (uv, object or world space), a node is in the part when every value it
// reads is Constant or K (variation.h) and it writes no MaterialOutputs. The cut's values are
// the K-valued outputs of the part that a node outside it reads: the output nodes read them
// too, so the material outputs that the part computes directly are among them. The part is
// evaluated at the key (EvaluateMaterialCut_<Name>) and its values cached; the rest
// (EvaluateMaterialRest_<Name>) recomputes what the part's constants and source nodes give
// it, which costs less than storing it, and reads the cut's values.
//
// A value with derivatives (a `_D` noise height under a Bump) crosses the cut as its value and
// its gradient along the key space's axes (u, v; or x, y, z of object or world space): its two
// derivatives are along the axes of the hit's own footprint (the ray cone's ellipse, thesis
// §2.2), so the filling ray's derivatives would be wrong for every other ray, but the gradient
// is the key's. The cut function evaluates its part with the footprint seeded along the key
// space's axes, one key step (the texel's or voxel's size) long, and once more along z in a
// 3D key space; the rest rebuilds the hit's derivatives by the chain rule from the hit's own
// key-space derivatives (dh/dx = grad h . dkey/dx). As Cycles' Bump takes its height's change
// over the footprint, the gradient is a finite difference over one key step, filtered at the
// key's level as the value is.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "compiler/resolved_graph.h"
#include "compiler/type_inference.h"
#include "compiler/variation.h"

namespace memograph::compiler {

// One value the cut hands to the rest: an output socket and where its floats start.
struct CutValue {
  std::size_t node = 0;
  std::size_t socket = 0;
  Type type;
  std::size_t offset = 0;  // in floats, into the cut's packed values
  // Key-space axes the value's gradient follows (2 for uv, 3 for object and world space), 0
  // for a value without derivatives. Packed as the value, then its change per unit along
  // each axis, each as wide as the value.
  std::size_t gradientAxes = 0;

  std::size_t width() const { return static_cast<std::size_t>(type.width()) * (1 + gradientAxes); }
};

// Key-space axes of a key domain: 2 for uv, 3 for object and world space.
std::size_t keySpaceAxes(Variation domain);

struct MaterialCut {
  // The key domain; Constant when the material has no cut.
  Variation domain = Variation::Constant;
  std::vector<CutValue> values;        // in emission order of their producers, then socket
  std::size_t width = 0;               // floats: the sum of the values' widths
  std::vector<std::size_t> cutNodes;   // evaluated by the cut function, emission order
  std::vector<std::size_t> restNodes;  // evaluated by the rest function, emission order
  double cachedCost = 0;  // estimated cost of the nodes only the cut function evaluates
  double totalCost = 0;   // estimated cost of the whole graph

  bool empty() const { return values.empty(); }
  bool hasGradients() const {
    for (const auto& value : values) {
      if (value.gradientAxes > 0)
        return true;
    }
    return false;
  }
  double cachedShare() const { return totalCost > 0 ? cachedCost / totalCost : 0.0; }
};

// The estimated cost of evaluating one node, in units of about one arithmetic node: its
// row of the cost table, or 1 for a node without one. Estimates until the table holds GPU
// timings (tools/bench/node_costs_device.sh; docs/design/memoization.md, "Measuring the node
// costs"); they rank domains and report a share.
double estimatedNodeCost(const ResolvedNode& node);

// The nodes the cost table names (every other node costs 1), in table order.
std::vector<std::string_view> nodesWithCostEstimates();

// The cut for one key domain (Uv, Object or World); empty when nothing with an estimated
// cost lies in it.
MaterialCut cutForDomain(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                         const OverloadChoice& chosen, const SocketVariation& variation,
                         Variation domain);

// The cut of the domain whose part holds the most estimated cost (ties: fewer floats, then
// uv, object, world); empty when no domain's part holds any.
MaterialCut findCut(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                    const OverloadChoice& chosen);

}  // namespace memograph::compiler
