// Writes a material's include for one target (thesis Listing 5.3, in SSA form): the prelude,
// the library functions the material uses (each under an include guard, callees first), and
// EvaluateMaterial_<Name>, with one variable per link, assigned exactly once.
#pragma once

#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/resolved_graph.h"
#include "compiler/type_inference.h"

namespace memograph::compiler {

struct EmitInput {
  const ResolvedGraph& graph;
  const std::vector<std::size_t>& order;
  const OverloadChoice& chosen;
  const NodeLibrary& library;
  const MaterialMetadata& metadata;
  std::string sourcePath;
};

std::string emitMaterial(const EmitInput& input, Target target);

}  // namespace memograph::compiler
