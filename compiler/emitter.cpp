#include "compiler/emitter.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "compiler/conversions.h"
#include "compiler/library_scanner.h"
#include "compiler/literal.h"

namespace memograph::compiler {

namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items)
    text += (text.empty() ? "" : ", ") + item;
  return text.empty() ? "none" : text;
}

// The function a node's call goes to: its chosen overload, or the library's specialisation
// of it for the first int input that is given a constant and has one (docs/guide/nodes.md,
// "Specialisations"), whose call then leaves that argument out.
struct NodeCall {
  std::size_t function = 0;
  std::optional<std::size_t> droppedParameter;
};

NodeCall callFor(const EmitInput& in, std::size_t node) {
  const auto& resolved = in.graph.nodes[node];
  const NodeType& type = *resolved.type;
  const std::size_t chosen = *in.chosen[node];
  const Overload& overload = type.overloads[chosen];
  for (std::size_t s = 0; s < type.sockets.size(); ++s) {
    const auto& input = resolved.inputs[s];
    if (type.sockets[s].direction != Direction::In ||
        overload.socketTypes[s].base != BaseType::Int || !input ||
        input->kind == InputSource::Kind::Link || input->constant.components.size() != 1)
      continue;
    const double value = input->constant.components[0];
    if (const auto special =
            in.library.specialisation(type, chosen, s, static_cast<long long>(value)))
      return {*special, type.sockets[s].parameterIndex};
  }
  return {overload.function, std::nullopt};
}

// Library functions reachable from each node's callee (`calls`), from the prelude functions a host
// shader may call (mg_make_float*_D, mg_defaultMaterialOutputs) and from what the
// material's function body calls itself (conversions, mg_const_*), for one target: the prelude's
// first, in definition order (the order in which they compile as one file), then the families' in
// call order, callees before callers.
std::vector<std::size_t> functionsToEmit(const EmitInput& in, Target target,
                                         const std::vector<NodeCall>& calls,
                                         const std::string& body) {
  const auto& functions = in.library.functions();
  std::vector<std::size_t> postOrder;
  std::vector<char> visited(functions.size(), 0);
  // Iterative post-order DFS over the call graph.
  auto visit = [&](std::size_t root) {
    if (visited[root] || !functions[root].isFor(target))
      return;
    std::vector<std::pair<std::size_t, std::size_t>> stack{{root, 0}};
    visited[root] = 1;
    while (!stack.empty()) {
      auto& [function, next] = stack.back();
      const auto& callees = functions[function].callees;
      if (next < callees.size()) {
        const std::size_t callee = callees[next++];
        if (!visited[callee] && functions[callee].isFor(target)) {
          visited[callee] = 1;
          stack.emplace_back(callee, 0);
        }
        continue;
      }
      postOrder.push_back(function);
      stack.pop_back();
    }
  };
  for (const std::size_t node : in.order)
    visit(calls[node].function);
  // What the including shader may call to build MaterialInputs and defaults
  // (docs/design/material-interface.md), then what the material's own function calls.
  auto roots = identifiersIn(body);
  roots.insert(roots.begin(), {"mg_make_float_D", "mg_make_float2_D", "mg_make_float3_D",
                               "mg_make_float4_D", "mg_defaultMaterialOutputs"});
  for (const auto identifier : roots) {
    for (const std::size_t function : in.library.functionsNamed(identifier)) {
      if (functions[function].prelude)
        visit(function);
    }
  }
  std::vector<std::size_t> result;
  for (const std::size_t function : postOrder) {
    if (functions[function].prelude)
      result.push_back(function);
  }
  std::sort(result.begin(), result.end());
  for (const std::size_t function : postOrder) {
    if (!functions[function].prelude)
      result.push_back(function);
  }
  return result;
}

std::string variableName(const ResolvedGraph& graph, std::size_t node, std::size_t socket) {
  if (const auto& link = graph.nodes[node].outputLinks[socket]) {
    return "link" + std::to_string(*link);
  }
  // An output nothing reads still needs a variable to be written to.
  return "unused" + std::to_string(node) + "_" + graph.nodes[node].type->sockets[socket].name;
}

// A constant table argument is a local variable filled entry by entry: the one spelling of
// an array-holding struct that GLSL and HLSL both accept (no initializer lists in GLSL, no
// struct constructors in HLSL).
std::string tableName(std::size_t node, const std::string& socket) {
  return "table" + std::to_string(node) + "_" + socket;
}

std::string tableDefinition(const std::string& name, const Literal& value) {
  std::string out = "  Table " + name + ";\n";
  const Type entry{BaseType::Float4, false};
  for (int i = 0; i < kTableEntries; ++i) {
    Literal rgba;
    rgba.kind = Literal::Kind::Tuple;
    rgba.components.assign(value.components.begin() + 4 * i, value.components.begin() + 4 * i + 4);
    out += "  " + name + ".v[" + std::to_string(i) + "] = " + formatConstant(rgba, entry) + ";\n";
  }
  return out;
}

// The floats a constant of `type` (float..float4) takes: as formatConstant spells them.
std::vector<float> constantFloats(const Literal& value, Type type) {
  std::vector<float> floats;
  for (int i = 0; i < type.width(); ++i)
    floats.push_back(static_cast<float>(literalComponent(value, i)));
  return floats;
}

// Where each float constant input that is a parameter starts in the parameter block
// (CompileOptions::parameterConstants): by (node, socket).
using ParameterSlots = std::map<std::pair<std::size_t, std::size_t>, std::size_t>;

// The slots of the constants that `parameter` picks (by index in `constants`, the graph's
// floatConstantInputs).
template <typename Picked>
ParameterSlots parameterSlots(const std::vector<FloatConstantInput>& constants, Picked parameter) {
  ParameterSlots slots;
  std::size_t next = 0;
  for (std::size_t i = 0; i < constants.size(); ++i) {
    if (!parameter(i))
      continue;
    slots[{constants[i].node, constants[i].socket}] = next;
    next += constants[i].floats.size();
  }
  return slots;
}

// A float constant read from the material's parameter block, floats first.. of it.
std::string parameterExpression(std::size_t first, Type type) {
  std::string code;
  for (int i = 0; i < type.width(); ++i) {
    code += std::string(i ? ", " : "") + "MG_MATERIAL_PARAMETER(" +
            std::to_string(first + static_cast<std::size_t>(i)) + ")";
  }
  const Type plain{type.base, false};
  if (type.width() > 1)
    code = plain.name() + "(" + code + ")";
  return type.derivatives ? "mg_const_" + type.name() + "(" + code + ")" : code;
}

std::string constantExpression(const Literal& value, Type type) {
  if (type.base == BaseType::TextureRef) {
    return std::to_string(static_cast<long long>(value.components.at(0)));
  }
  if (!type.derivatives)
    return formatConstant(value, type);
  const Type plain{type.base, false};
  return "mg_const_" + type.name() + "(" + formatConstant(value, plain) + ")";
}

// The body of a function that evaluates `nodes` (a subsequence of the emission order): one
// declaration per output, then the constant tables, then one call per node, as in thesis
// Listing 5.3.
std::string nodeStatements(const EmitInput& in, const std::vector<NodeCall>& calls,
                           const ParameterSlots& parameters,
                           const std::vector<std::size_t>& nodes) {
  std::string text;
  for (const std::size_t node : nodes) {
    const auto& resolved = in.graph.nodes[node];
    const auto& overload = resolved.type->overloads[*in.chosen[node]];
    for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
      if (resolved.type->sockets[s].direction != Direction::Out)
        continue;
      text += "  " + overload.socketTypes[s].name() + " " + variableName(in.graph, node, s) + ";\n";
    }
  }
  for (const std::size_t node : nodes) {
    const auto& resolved = in.graph.nodes[node];
    const auto& overload = resolved.type->overloads[*in.chosen[node]];
    for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
      if (overload.socketTypes[s].base == BaseType::Table && resolved.inputs[s] &&
          resolved.inputs[s]->kind != InputSource::Kind::Link) {
        text += tableDefinition(tableName(node, resolved.type->sockets[s].name),
                                resolved.inputs[s]->constant);
      }
    }
  }
  for (const std::size_t node : nodes) {
    const auto& resolved = in.graph.nodes[node];
    const auto& type = *resolved.type;
    const auto& overload = type.overloads[*in.chosen[node]];
    const auto& function = in.library.functions()[overload.function];
    std::vector<std::string> arguments(function.parameters.size());
    for (std::size_t p = 0; p < function.parameters.size(); ++p) {
      const auto base = function.parameters[p].type.base;
      if (base == BaseType::Inputs)
        arguments[p] = "inputs";
      if (base == BaseType::Outputs)
        arguments[p] = "outputs";
    }
    for (std::size_t s = 0; s < type.sockets.size(); ++s) {
      const Type wanted = overload.socketTypes[s];
      std::string& argument = arguments[type.sockets[s].parameterIndex];
      if (type.sockets[s].direction == Direction::Out) {
        argument = variableName(in.graph, node, s);
        continue;
      }
      const InputSource& source = *resolved.inputs[s];
      if (source.kind != InputSource::Kind::Link) {
        const auto parameter = parameters.find({node, s});
        argument = wanted.base == BaseType::Table  ? tableName(node, type.sockets[s].name)
                   : parameter != parameters.end() ? parameterExpression(parameter->second, wanted)
                                                   : constantExpression(source.constant, wanted);
        continue;
      }
      const auto& producer = in.graph.nodes[source.producer];
      const Type produced =
          producer.type->overloads[*in.chosen[source.producer]].socketTypes[source.producerSocket];
      argument = convertExpression(variableName(in.graph, source.producer, source.producerSocket),
                                   produced, wanted);
    }
    const NodeCall& callee = calls[node];
    if (callee.droppedParameter)
      arguments.erase(arguments.begin() + static_cast<std::ptrdiff_t>(*callee.droppedParameter));
    std::string call = "  " + in.library.functions()[callee.function].name + "(";
    for (std::size_t i = 0; i < arguments.size(); ++i)
      call += (i ? ", " : "") + arguments[i];
    text += call + ");\n";
  }
  return text;
}

// The name of component `i` of a value of `width` floats: the value itself, or .x .. .w.
std::string component(const std::string& variable, int width, int i) {
  static const char* const kSwizzle[] = {".x", ".y", ".z", ".w"};
  return width == 1 ? variable : variable + kSwizzle[i];
}

// The MaterialInputs member whose derivatives a key domain's gradients follow: the key
// space's coordinates at the hit.
std::string keySpaceMember(Variation domain) {
  switch (domain) {
    case Variation::Uv:
      return "uv";
    case Variation::Object:
      return "objectPosition";
    default:
      return "position";
  }
}

// Statements indented by two more spaces (a loop's body).
std::string indented(const std::string& statements) {
  std::string text;
  std::size_t begin = 0;
  while (begin < statements.size()) {
    const std::size_t end = statements.find('\n', begin);
    const std::size_t next = end == std::string::npos ? statements.size() : end + 1;
    if (next - begin > 1)
      text += "  ";
    text += statements.substr(begin, next - begin);
    begin = next;
  }
  return text;
}

// The packing of one cut value into cut.v: its value, or with `axisRun` its change per key
// unit along the run's key axes (cut.h, CutValue): run 0 packs the value and axes 0 and 1
// (the footprint's x and y), run 1 axis 2 (the footprint's x along z).
std::string packedValue(const EmitInput& in, const CutValue& value, int axisRun,
                        const std::string& indent) {
  const std::string variable = variableName(in.graph, value.node, value.socket);
  const int width = value.type.width();
  std::string text;
  auto store = [&](std::size_t slot, const std::string& expression) {
    text += indent + "cut.v[" + std::to_string(value.offset + slot) + "] = " + expression + ";\n";
  };
  for (int i = 0; i < width; ++i) {
    const auto component_i = static_cast<std::size_t>(i);
    if (value.gradientAxes == 0) {
      store(component_i, component(variable, width, i));
      continue;
    }
    const std::size_t w = static_cast<std::size_t>(width);
    if (axisRun == 0) {
      store(component_i, component(variable + ".v", width, i));
      store(w + component_i, component(variable + ".x", width, i) + " / keyStep");
      store(2 * w + component_i, component(variable + ".y", width, i) + " / keyStep");
    } else {
      store(3 * w + component_i, component(variable + ".x", width, i) + " / keyStep");
    }
  }
  return text;
}

// `float3(cut.v[a], cut.v[a + 1], cut.v[a + 2])`, or `cut.v[a]` for one float.
std::string packedVector(std::size_t first, int width) {
  std::string packed;
  for (int i = 0; i < width; ++i) {
    packed += std::string(i ? ", " : "") + "cut.v[" +
              std::to_string(first + static_cast<std::size_t>(i)) + "]";
  }
  return width == 1 ? packed : Type::floatOfWidth(width, false).name() + "(" + packed + ")";
}

// The rest's unpacking of one cut value: as packed, or for a gradient value its derivatives
// along the hit's footprint axes by the chain rule, d/dx = sum_k grad_k (d key_k / dx).
std::string unpackedValue(const EmitInput& in, const CutValue& value) {
  const std::string variable = variableName(in.graph, value.node, value.socket);
  const int width = value.type.width();
  if (value.gradientAxes == 0)
    return "  " + value.type.name() + " " + variable + " = " + packedVector(value.offset, width) +
           ";\n";
  static const char* const kAxis[] = {".x", ".y", ".z"};
  const std::string key = "inputs." + keySpaceMember(in.cut.domain);
  const auto w = static_cast<std::size_t>(width);
  auto along = [&](const char* footprintAxis) {
    std::string sum;
    for (std::size_t k = 0; k < value.gradientAxes; ++k) {
      sum += std::string(k ? " + " : "") + packedVector(value.offset + (k + 1) * w, width) + " * " +
             key + footprintAxis + kAxis[k];
    }
    return sum;
  };
  return "  " + value.type.name() + " " + variable + " = mg_make_" + value.type.name() + "(" +
         packedVector(value.offset, width) + ",\n      " + along(".x") + ",\n      " + along(".y") +
         ");\n";
}

// The key-space footprint a gradient cut's part runs with (cut.h): `inputs` is `keyInputs`
// with the key member's derivatives one key step along the run's axes (run 0: x and y; run 1:
// z, in a 3D key space), and Generated's following the object-space position's.
std::string keyAxesSeeding(Variation domain) {
  const std::string key = "inputs." + keySpaceMember(domain);
  if (domain == Variation::Uv) {
    return "  MaterialInputs inputs = keyInputs;\n  " + key + ".x = float2(keyStep, 0.0);\n  " +
           key + ".y = float2(0.0, keyStep);\n";
  }
  std::string text = "    MaterialInputs inputs = keyInputs;\n    " + key +
                     ".x = float3(axisRun == 0 ? keyStep : 0.0, 0.0, axisRun == 1 ? keyStep : "
                     "0.0);\n    " +
                     key + ".y = float3(0.0, axisRun == 0 ? keyStep : 0.0, 0.0);\n";
  if (domain == Variation::Object) {
    text +=
        "    inputs.generated.x = inputs.objectPosition.x * inputs.generatedScale;\n"
        "    inputs.generated.y = inputs.objectPosition.y * inputs.generatedScale;\n";
  }
  return text;
}

// MaterialCut_<Name>, EvaluateMaterialCut_<Name> and EvaluateMaterialRest_<Name> (cut.h):
// the cut function runs the part that the key determines and packs the values that leave it
// into floats; the rest unpacks them into the variables EvaluateMaterial_<Name> gives them
// and runs everything else, so that rest(inputs, cut(inputs)) computes what
// EvaluateMaterial_<Name>(inputs) does (for gradient values, up to the gradient's finite
// difference over one key step against the hit's over its footprint).
std::string cutFunctions(const EmitInput& in, const std::vector<NodeCall>& calls,
                         const ParameterSlots& parameters) {
  const MaterialCut& cut = in.cut;
  const std::string& name = in.metadata.name;
  const std::string domain(variationName(cut.domain));
  std::string text = "\n// The values of " + name + " that only " + domain +
                     " space and constants determine: " + std::to_string(cut.values.size()) +
                     (cut.values.size() == 1 ? " value" : " values") + " in " +
                     std::to_string(cut.width) + " floats.\n";
  text += "struct MaterialCut_" + name + " {\n  float v[" + std::to_string(cut.width) + "];\n};\n";
  text += "\n// Only the " + domain +
          "-space members of inputs reach the packed values; the others may hold\n"
          "// placeholders.\n";
  if (!cut.hasGradients()) {
    text += "void EvaluateMaterialCut_" + name + "(in MaterialInputs inputs, out MaterialCut_" +
            name + " cut) {\n";
    text += nodeStatements(in, calls, parameters, cut.cutNodes);
    for (const CutValue& value : cut.values)
      text += packedValue(in, value, 0, "  ");
    text += "}\n";
  } else {
    const std::string key = "keyInputs." + keySpaceMember(cut.domain);
    text +=
        "// Values with derivatives are packed with their gradient along the key space's axes,\n"
        "// a finite difference over one key step: the footprint's shorter axis, which at a\n"
        "// key is its texel's or voxel's size.\n";
    text += "void EvaluateMaterialCut_" + name + "(in MaterialInputs keyInputs, out MaterialCut_" +
            name + " cut) {\n";
    text += "  float keyStep = max(min(length(" + key + ".x), length(" + key + ".y)), 1.0e-5);\n";
    std::string packing0;
    std::string packing1;
    const bool threeAxes = keySpaceAxes(cut.domain) == 3;
    for (const CutValue& value : cut.values) {
      packing0 += packedValue(in, value, 0, threeAxes ? "      " : "  ");
      if (value.gradientAxes == 3)
        packing1 += packedValue(in, value, 1, "      ");
    }
    if (!threeAxes) {
      text += keyAxesSeeding(cut.domain);
      text += nodeStatements(in, calls, parameters, cut.cutNodes);
      text += packing0;
    } else {
      text += "  for (int axisRun = 0; axisRun < 2; ++axisRun) {\n";
      text += keyAxesSeeding(cut.domain);
      text += indented(nodeStatements(in, calls, parameters, cut.cutNodes));
      text += "    if (axisRun == 0) {\n" + packing0 + "    } else {\n" + packing1 + "    }\n";
      text += "  }\n";
    }
    text += "}\n";
  }
  text += "\nvoid EvaluateMaterialRest_" + name + "(in MaterialInputs inputs, in MaterialCut_" +
          name + " cut, out MaterialOutputs outputs) {\n";
  text += "  outputs = mg_defaultMaterialOutputs(inputs);\n";
  for (const CutValue& value : cut.values)
    text += unpackedValue(in, value);
  text += nodeStatements(in, calls, parameters, cut.restNodes);
  return text + "}\n";
}

}  // namespace

std::vector<FloatConstantInput> floatConstantInputs(const EmitInput& in) {
  std::vector<FloatConstantInput> constants;
  for (const std::size_t node : in.order) {
    const auto& resolved = in.graph.nodes[node];
    const auto& overload = resolved.type->overloads[*in.chosen[node]];
    for (std::size_t s = 0; s < resolved.type->sockets.size(); ++s) {
      const Type wanted = overload.socketTypes[s];
      if (resolved.type->sockets[s].direction != Direction::In || !resolved.inputs[s] ||
          resolved.inputs[s]->kind == InputSource::Kind::Link || !wanted.isFloat())
        continue;
      constants.push_back({node, s, constantFloats(resolved.inputs[s]->constant, wanted)});
    }
  }
  return constants;
}

namespace {

// EvaluateMaterial_<Name>, then the cut's functions where the material has a cut.
std::string materialFunctions(const EmitInput& in, const std::vector<NodeCall>& calls,
                              const ParameterSlots& parameters) {
  std::string body = "\nvoid EvaluateMaterial_" + in.metadata.name +
                     "(in MaterialInputs inputs, out MaterialOutputs outputs) {\n";
  body += "  outputs = mg_defaultMaterialOutputs(inputs);\n";
  body += nodeStatements(in, calls, parameters, in.order);
  body += "}\n";
  return in.cut.empty() ? body : body + cutFunctions(in, calls, parameters);
}

std::vector<NodeCall> nodeCalls(const EmitInput& in) {
  std::vector<NodeCall> calls(in.graph.nodes.size());
  for (const std::size_t node : in.order)
    calls[node] = callFor(in, node);
  return calls;
}

}  // namespace

std::string materialShape(const EmitInput& in, const std::string& placeholder) {
  MaterialMetadata renamed = in.metadata;
  renamed.name = placeholder;
  const EmitInput shape{in.graph, in.order, in.chosen, in.library, renamed, in.cut, in.sourcePath};
  return materialFunctions(
      shape, nodeCalls(shape),
      parameterSlots(floatConstantInputs(in), [](std::size_t) { return true; }));
}

std::string emitMaterial(const EmitInput& in, Target target) {
  const bool glsl = target == Target::Glsl;
  const auto& meta = in.metadata;
  std::string out;
  out += "// Generated by memograph from " + in.sourcePath + ". Do not edit.\n";
  out += "// Material " + meta.name + ": " + std::to_string(meta.nodeCount) + " nodes, " +
         (meta.cacheable ? "cacheable" : "not cacheable") + ", inputs: " + joined(meta.inputsUsed) +
         ", outputs: " + joined(meta.outputsWritten) + "\n";
  for (std::size_t slot = 0; slot < meta.textures.size(); ++slot) {
    out += "// texture slot " + std::to_string(slot) + ": " + meta.textures[slot] + "\n";
  }
  // Each node's callee, once: the call below and the functions to emit follow it.
  const std::vector<NodeCall> calls = nodeCalls(in);
  // The functions first: what they call decides which library functions come before them.
  // The constants are looked for only when some are parameters (material instances).
  const std::vector<bool>& picked = in.parameterConstants;
  const ParameterSlots parameters =
      std::find(picked.begin(), picked.end(), true) == picked.end()
          ? ParameterSlots{}
          : parameterSlots(floatConstantInputs(in),
                           [&](std::size_t i) { return i < picked.size() && picked[i]; });
  const std::string functions = materialFunctions(in, calls, parameters);

  // The prelude's declarations (types, defines, prototypes) once per shader; then each
  // reached function once, under its own guard, so that any number of material includes
  // can share one shader.
  const std::string preludeGuard = glsl ? "MG_PRELUDE_GLSL" : "MG_PRELUDE_HLSL";
  out += "\n#ifndef " + preludeGuard + "\n#define " + preludeGuard + "\n";
  out += in.library.preludeDeclarations(target);
  out += "#endif  // " + preludeGuard + "\n";
  for (const std::size_t index : functionsToEmit(in, target, calls, functions)) {
    const auto& function = in.library.functions()[index];
    out += "\n#ifndef " + function.guard + "\n#define " + function.guard + "\n";
    out += function.text + "\n#endif\n";
  }
  return out + functions;
}

}  // namespace memograph::compiler
