// The graph after name resolution: every node bound to its NodeType, every input socket to
// its source (a producer's output, a constant, or the socket's default), every output to its
// consumers. Later passes (schedule, inference, emission) read and annotate this.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/graph.h"
#include "compiler/node_library.h"

namespace memograph::compiler {

struct InputSource {
  enum class Kind { Link, Constant, Default };
  Kind kind = Kind::Link;
  std::size_t producer = 0;        // Link: node index
  std::size_t producerSocket = 0;  // Link: socket index in the producer's NodeType
  std::int64_t link = 0;           // Link: the id written in the graph
  Literal constant;                // Constant, Default
  SourceLocation location;
};

struct Consumer {
  std::size_t node = 0;
  std::size_t socket = 0;
};

struct ResolvedNode {
  const NodeType* type = nullptr;
  const Node* source = nullptr;
  std::vector<std::optional<InputSource>> inputs;        // per socket; set for input sockets
  std::vector<std::optional<std::int64_t>> outputLinks;  // per socket; set when linked
  std::vector<std::vector<Consumer>> consumers;          // per socket
};

struct ResolvedGraph {
  std::string name;
  std::vector<ResolvedNode> nodes;    // parallel to Graph::nodes
  std::vector<std::string> textures;  // string constants bound to TextureRef, slot order
};

// The longest material name: it names <name>.glsl/.hlsl/.json and their temporary files
// (".<name>.XXXXXX.glsl.old"), which must fit the 255-byte file-name limit of common file
// systems; checked here so that `check` and `compile` agree.
inline constexpr std::size_t kMaxMaterialNameLength = 200;

// Binds names and links. Reports unknown nodes (with did-you-mean), unknown sockets, links
// produced twice or never, unbound inputs, misplaced literals.
std::optional<ResolvedGraph> resolveGraph(const Graph& graph, const SourceFile& file,
                                          const NodeLibrary& library, Diagnostics& diagnostics);

}  // namespace memograph::compiler
