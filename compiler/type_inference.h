// Overload selection, which fixes every edge's type and whether it carries derivatives
// (thesis §5.1): phase 1 filters overloads from the sinks, phase 2 from the sources
// (repeated to a fixed point: arc consistency), phase 3 searches what remains for the
// cheapest assignment (see Cost in conversions.h).
#pragma once

#include <optional>
#include <vector>

#include "compiler/conversions.h"
#include "compiler/diagnostics.h"
#include "compiler/resolved_graph.h"

namespace memograph::compiler {

// Per node index: the chosen index into its NodeType::overloads (unset for pruned nodes).
using OverloadChoice = std::vector<std::optional<std::size_t>>;

std::optional<OverloadChoice> inferTypes(const ResolvedGraph& graph,
                                         const std::vector<std::size_t>& order,
                                         const SourceFile& file, Diagnostics& diagnostics);

// The cost of feeding a constant to a socket of type `to`, or nothing if it cannot.
std::optional<Cost> constantCost(const Literal& value, Type to);

// "Mix(float3 A, float3 B, float Factor) -> float3 Out" for messages and `memograph nodes`.
std::string overloadSignature(const NodeType& type, const Overload& overload);

}  // namespace memograph::compiler
