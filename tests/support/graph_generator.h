// Deterministic random material graphs (.mgraph text) for benchmarks and fuzzing: valid
// graphs of a requested size built from the nodes of the test library
// (tests/compiler/testdata/nodes), shaped like hand-made materials.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "compiler/node_library.h"
#include "compiler/source_file.h"

namespace memograph::testing {

struct GraphShape {
  std::size_t nodeCount = 100;  // exact number of nodes in the graph (at least 1)
  std::uint64_t seed = 1;       // same shape and seed, same text, on every platform
  // Adds UV → Mul → ImageTexture chains, whose edges must carry derivatives.
  bool textures = true;
  std::string materialName;  // declared with `material Name;` when not empty
};

// A graph that compiles with the test library: several sources (constants, UV, normal,
// position, time), a DAG with fan-out and reconvergence, `Socket=value` and positional
// constants, every node reaching an output, statements in shuffled order.
std::string generateGraph(const GraphShape& shape);

// `count` graphs of `nodeCount` nodes with seeds firstSeed, firstSeed + 1, …, named
// "generated_<seed>.mgraph".
std::vector<compiler::SourceFile> generateGraphSet(std::size_t count, std::size_t nodeCount,
                                                   std::uint64_t firstSeed);

// The test node library's directory (tests/compiler/testdata/nodes in the source tree).
std::string testNodeLibraryDirectory();

// The test node library, loaded once; aborts with its diagnostics if it does not load.
const compiler::NodeLibrary& testNodeLibrary();

}  // namespace memograph::testing
