// The parsed, untyped material graph (thesis Listing 5.1): nodes with sockets bound to link
// ids or constants. Types are unknown here; passes after parsing add them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compiler/source_file.h"

namespace memograph::compiler {

// A constant written in the graph: a number, a tuple `(0.8, 0.2, 0.1)` or a string.
struct Literal {
  enum class Kind { Number, Tuple, String, Table };
  Kind kind = Kind::Number;
  std::vector<double> components;  // Number: one; Tuple: two to four; Table: kTableNumbers
  bool isInteger = false;          // Number written without '.' or exponent
  std::string text;                // String: the unquoted text
  SourceLocation location;
};

struct LinkBinding {
  std::string socket;
  std::int64_t link = 0;
  SourceLocation location;  // of the socket name
};

struct ConstantBinding {
  std::string socket;
  Literal value;
  SourceLocation location;  // of the socket name
};

struct Node {
  std::string type;
  SourceLocation location;                 // of the type name
  std::vector<LinkBinding> inputs;         // Socket<id
  std::vector<LinkBinding> outputs;        // Socket>id
  std::vector<ConstantBinding> constants;  // Socket=value
  std::vector<Literal> positional;         // bare literals, in order
};

struct Graph {
  std::string name;  // from `material Name;`, else the file stem
  SourceLocation nameLocation;
  std::vector<Node> nodes;
};

}  // namespace memograph::compiler
