// The node library: overloads parsed from the function signatures in nodes/*.inc
// (thesis §5.1; format in docs/node-library.md), with template instantiation and the
// bodies needed to emit each function.
#pragma once

#include <map>
#include <memory>
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

// One emitted function: a node overload or a helper, after template instantiation.
struct LibraryFunction {
  std::string name;
  std::string returnType;
  std::vector<Parameter> parameters;
  std::string text;                  // the whole instantiated definition, ready to emit
  std::string guard;                 // include-guard macro, unique per name and parameter types
  std::string file;                  // library file it came from
  SourceLocation location;           // of the definition in that file
  std::vector<std::size_t> callees;  // library functions it calls (NodeLibrary::functions())
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
  // Every function of the node families (nodes and helpers), in definition order.
  const std::vector<LibraryFunction>& functions() const { return parts_.functions; }
  // The prelude for a target: its target-specific file then common.inc, templates expanded.
  const std::string& prelude(Target target) const {
    return target == Target::Glsl ? parts_.glslPrelude : parts_.hlslPrelude;
  }

  struct Parts {
    std::vector<NodeType> nodeTypes;
    std::vector<LibraryFunction> functions;
    std::string glslPrelude;
    std::string hlslPrelude;
  };

 private:
  Parts parts_;
};

}  // namespace memograph::compiler
