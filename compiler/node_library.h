// The node library: overloads parsed from the function signatures in nodes/*.inc
// (thesis §5.1; format in docs/guide/nodes.md), with template instantiation and the
// bodies needed to emit each function.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/graph.h"
#include "compiler/source_file.h"
#include "compiler/types.h"

namespace memograph::compiler {

enum class Direction { In, Out, InOut };

struct Parameter {
  Direction direction = Direction::In;
  Type type;
  std::string name;
};

// One emitted function: a node overload, a helper, or a function of the prelude, after
// template instantiation. All three are emitted only when a material reaches them.
struct LibraryFunction {
  std::string name;
  std::string returnType;
  std::vector<Parameter> parameters;        // nodes only (prelude and helper types stay text)
  std::vector<std::string> parameterTypes;  // every function: each parameter's type as written
  std::string text;                         // the whole instantiated definition, ready to emit
  std::string guard;        // include-guard macro, unique per name and parameter types
  std::string file;         // library file it came from
  SourceLocation location;  // of the definition in that file
  // Library functions it calls (NodeLibrary::functions()), by name: every overload of a
  // called name, and of its own name only the overloads defined before it (the only ones a
  // shader compiler lets it call).
  std::vector<std::size_t> callees;
  bool prelude = false;              // defined in prelude/ (else in a node family file)
  std::optional<Target> onlyTarget;  // prelude/glsl.inc or prelude/hlsl.inc: that target only

  bool isFor(Target target) const { return !onlyTarget || *onlyTarget == target; }
};

// A socket of a node type: a parameter that is not a context parameter.
struct Socket {
  std::string name;
  Direction direction = Direction::In;
  std::size_t parameterIndex = 0;  // position in LibraryFunction::parameters
};

struct Overload {
  std::size_t function = 0;       // index into NodeLibrary::functions()
  std::vector<Type> socketTypes;  // parallel to NodeType::sockets
  int derivativeInputs = 0;       // input sockets of a `_D` type
  int derivativeOutputs = 0;      // output sockets of a `_D` type
  // Gives `_D` outputs that would be invented: a source node (no input sockets) reading only
  // MaterialInputs members that vary over a footprint but carry no derivatives (normal,
  // tangent, vertexColor, view, geometricNormal). Type inference never chooses it
  // (docs/guide/graph-format.md, "Derivatives").
  bool inventsDerivatives = false;
};

// All overloads of one node name, which share their sockets.
struct NodeType {
  std::string name;
  std::string description;
  std::vector<Socket> sockets;
  std::map<std::string, Literal> defaults;  // socket → @default value
  std::vector<std::string> inputsRead;      // @input
  std::vector<std::string> outputsWritten;  // @output
  bool isSink = false;                      // writes MaterialOutputs
  bool takesInputs = false;                 // reads MaterialInputs
  std::vector<Overload> overloads;
  std::string file;
  SourceLocation location;

  int socketIndex(std::string_view socketName) const;  // -1 when absent
};

class NodeLibrary {
 public:
  // Parses every file; problems in the library are reported with file:line:col. Files
  // under "prelude/" form the prelude; the rest are node families.
  static NodeLibrary load(const std::vector<SourceFile>& files, Diagnostics& diagnostics);

  const NodeType* find(std::string_view name) const;
  // Up to three known node names closest to `name` (edit distance), best first.
  std::vector<std::string> suggestions(std::string_view name) const;

  const std::vector<NodeType>& nodeTypes() const { return parts_.nodeTypes; }  // by name
  // Every function: the prelude's (target-specific file first, then common.inc), then the
  // node families' (nodes and helpers), in definition order.
  const std::vector<LibraryFunction>& functions() const { return parts_.functions; }
  // Indices into functions() of every function (any target) named `name`, in definition
  // order; empty when there is none.
  const std::vector<std::size_t>& functionsNamed(std::string_view name) const;
  // A node overload's specialisation for a constant int socket (docs/guide/nodes.md,
  // "Specialisations"): the helper mg_spec_<Node>_<Socket>_<value> whose parameters are the
  // overload's without that socket, or none. The emitter calls it instead of the overload, so
  // that the shader compilers never see the overload's other branches.
  std::optional<std::size_t> specialisation(const NodeType& node, std::size_t overload,
                                            std::size_t socket, long long value) const;
  // The whole prelude for a target: its target-specific file then common.inc, templates
  // expanded, each function under its include guard (LibraryFunction::guard), so that it can
  // precede material includes, which emit the prelude functions they reach under the same
  // guards.
  const std::string& prelude(Target target) const {
    return target == Target::Glsl ? parts_.glslPrelude : parts_.hlslPrelude;
  }
  // What every material include carries of the prelude: its preprocessor lines, structs
  // (float*_D, Table, MaterialInputs, MaterialOutputs) and prototypes, in file order.
  const std::string& preludeDeclarations(Target target) const {
    return target == Target::Glsl ? parts_.glslDeclarations : parts_.hlslDeclarations;
  }

  struct Parts {
    std::vector<NodeType> nodeTypes;
    std::vector<LibraryFunction> functions;
    std::map<std::string, std::vector<std::size_t>, std::less<>> functionsByName;
    std::string glslPrelude;
    std::string hlslPrelude;
    std::string glslDeclarations;
    std::string hlslDeclarations;
  };

 private:
  Parts parts_;
};

}  // namespace memograph::compiler
