// Per-material metadata for the runtime (thesis §4.2: which materials may be memoized).
#pragma once

#include <string>

#include "compiler/compiler.h"
#include "compiler/cut.h"
#include "compiler/resolved_graph.h"
#include "compiler/type_inference.h"

namespace memograph::compiler {

MaterialMetadata collectMetadata(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                                 const OverloadChoice& chosen, const MaterialCut& cut);

// A cost share (0..1) as the metadata writes it: "0.875".
std::string formatShare(double share);

// A small JSON object; keys in a fixed order so the file is byte-identical across runs.
std::string metadataToJson(const MaterialMetadata& metadata);

}  // namespace memograph::compiler
