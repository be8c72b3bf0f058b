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
// Derivatives do not cross the cut. A `_D` value's two derivatives are along the axes of the
// hit's own footprint (the ray cone's ellipse, thesis §2.2), so a cached value's derivatives
// would be the filling ray's axes, wrong for every other ray: a producer whose `_D` output a
// node outside the part reads (a noise height under a Bump) is left out of the part, and so,
// in turn, are producers of its `_D` inputs. Inside the part, derivatives are as correct as
// the whole-graph cache's: the part runs with the key's footprint (the cache level's texel).
// Caching a height with its gradient along the key's axes, from which the rest would rebuild
// the hit's derivatives by the chain rule, would keep such producers in; it needs a second
// derivative seeding of the part and is not done.
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
};

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
