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
  // CompileOptions::parameterConstants, by index in floatConstantInputs().
  std::vector<bool> parameterConstants = {};
};

std::string emitMaterial(const EmitInput& input, Target target);

// A float constant input: node `node`'s input socket `socket`, given `floats` (a number splat
// to the socket's width).
struct FloatConstantInput {
  std::size_t node = 0;
  std::size_t socket = 0;
  std::vector<float> floats;
};

// The graph's float constant inputs (CompiledMaterial::floatConstants) in emission order.
std::vector<FloatConstantInput> floatConstantInputs(const EmitInput& input);

// The material's functions alone (EvaluateMaterial_<Name> and the cut's), every float
// constant a parameter and the name `placeholder`: CompiledMaterial::shape.
std::string materialShape(const EmitInput& input, const std::string& placeholder);

}  // namespace memograph::compiler
