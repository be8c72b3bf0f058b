// Orders the nodes for emission by depth-first search from the graph outputs (thesis §5.1),
// dropping nodes that reach no output, and reports cycles and graphs without outputs.
#pragma once

#include <optional>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/resolved_graph.h"

namespace memograph::compiler {

// Node indices, producers before consumers. Unreachable nodes get a warning.
std::optional<std::vector<std::size_t>> scheduleGraph(const ResolvedGraph& graph,
                                                      const SourceFile& file,
                                                      Diagnostics& diagnostics);

}  // namespace memograph::compiler
