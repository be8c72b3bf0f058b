// Writes a material's include for one target (thesis Listing 5.3, in SSA form): the prelude,
// the library functions the material uses (each under an include guard, callees first), and
// EvaluateMaterial_<Name>, with one variable per link, assigned exactly once; after it, when
// the material has a cut (compiler/cut.h), MaterialCut_<Name>, EvaluateMaterialCut_<Name>
// and EvaluateMaterialRest_<Name>.
#pragma once

#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/cut.h"
#include "compiler/resolved_graph.h"
#include "compiler/type_inference.h"

namespace memograph::compiler {

struct EmitInput {
  const ResolvedGraph& graph;
  const std::vector<std::size_t>& order;
  const OverloadChoice& chosen;
  const NodeLibrary& library;
  const MaterialMetadata& metadata;
  const MaterialCut& cut;
  std::string sourcePath;
};

std::string emitMaterial(const EmitInput& input, Target target);

}  // namespace memograph::compiler
