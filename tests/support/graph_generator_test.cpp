// The generator's promises: valid graphs of the exact size, deterministic per seed, with
// derivatives exactly when textures are asked for, and shaped like a DAG with fan-out.
#include "graph_generator.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "compiler/compiler.h"

namespace memograph::testing {
namespace {

TEST(GraphGenerator, GraphsCompileWithoutDiagnosticsAndKeepEveryNode) {
  for (const std::size_t nodes : {1, 2, 3, 5, 8, 17, 64, 100, 1000}) {
    const std::uint64_t seeds = nodes >= 1000 ? 3 : 25;
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
      for (const bool textures : {true, false}) {
        const GraphShape shape{nodes, seed, textures, ""};
        const compiler::SourceFile file{"generated.mgraph", generateGraph(shape)};
        compiler::Diagnostics diagnostics;
        const auto compiled = compiler::compileMaterial(file, testNodeLibrary(), {}, diagnostics);
        ASSERT_TRUE(compiled && diagnostics.all().empty())
            << nodes << " nodes, seed " << seed << ", textures " << textures << ":\n"
            << compiler::formatDiagnostics(diagnostics) << file.text;
        EXPECT_EQ(compiled->metadata.nodeCount, nodes) << "every node must reach an output";
        EXPECT_EQ(compiled->metadata.needsDerivatives, textures && nodes >= 5)
            << nodes << " nodes, seed " << seed;
      }
    }
  }
}

TEST(GraphGenerator, SameShapeAndSeedGiveTheSameText) {
  const GraphShape shape{300, 42, true, "Stone"};
  EXPECT_EQ(generateGraph(shape), generateGraph(shape));
  EXPECT_NE(generateGraph(shape), generateGraph({300, 43, true, "Stone"}));
  EXPECT_NE(generateGraph(shape).find("material Stone;"), std::string::npos);
}

TEST(GraphGenerator, LargeGraphsHaveFanOutAndManySources) {
  const compiler::SourceFile file{"generated.mgraph", generateGraph({1000, 7, true, ""})};
  compiler::Diagnostics diagnostics;
  const auto report = compiler::checkMaterial(file, testNodeLibrary(), diagnostics);
  ASSERT_TRUE(report) << compiler::formatDiagnostics(diagnostics);
  const auto fannedOut = std::count_if(report->links.begin(), report->links.end(),
                                       [](const auto& link) { return link.consumers.size() > 1; });
  EXPECT_GT(fannedOut, 50);
  const auto sources = std::count_if(report->nodes.begin(), report->nodes.end(), [](const auto& n) {
    return n.starts_with("Float1Constant") || n.starts_with("Float3Constant") ||
           n.starts_with("UVInput") || n.starts_with("NormalInput") ||
           n.starts_with("PositionInput") || n.starts_with("TimeInput");
  });
  EXPECT_GT(sources, 50);
}

TEST(GraphGenerator, SetNamesEachGraphAfterItsSeed) {
  const auto graphs = generateGraphSet(3, 20, 10);
  ASSERT_EQ(graphs.size(), 3u);
  EXPECT_EQ(graphs[2].path, "generated_12.mgraph");
  EXPECT_EQ(graphs[2].text, generateGraph({20, 12, true, ""}));
}

}  // namespace
}  // namespace memograph::testing
