// Google Benchmark timings of the compiler (targets on the 2-core machine: a
// 1,000-node graph under 10 ms, 100 graphs of 100 nodes under 100 ms), and of loading the
// node library (the test one and the real one). Graphs come from the deterministic
// generator; the library is loaded outside the timed loops.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/parser.h"
#include "graph_generator.h"
#include "memograph/node_library_loader.h"

namespace {

using namespace memograph;

// Parse, resolve, schedule, infer and emit GLSL and HLSL; fails the run on any diagnostic
// so a broken generator cannot produce a fast, meaningless figure.
void compileOrFail(benchmark::State& state, const compiler::SourceFile& graph) {
  compiler::Diagnostics diagnostics;
  auto compiled = compiler::compileMaterial(graph, testing::testNodeLibrary(), {}, diagnostics);
  if (!compiled || !diagnostics.all().empty()) {
    state.SkipWithError(("compile failed: " + compiler::formatDiagnostics(diagnostics)).c_str());
    return;
  }
  benchmark::DoNotOptimize(compiled->glsl.data());
  benchmark::DoNotOptimize(compiled->hlsl.data());
}

void BM_CompileOneGraph(benchmark::State& state) {
  testing::GraphShape shape;
  shape.nodeCount = static_cast<std::size_t>(state.range(0));
  shape.seed = 1;
  const compiler::SourceFile graph{"generated.mgraph", testing::generateGraph(shape)};
  testing::testNodeLibrary();
  for (auto _ : state)
    compileOrFail(state, graph);
  state.counters["nodes/s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * state.range(0)), benchmark::Counter::kIsRate);
}
// Medians of 10 repetitions: the 2-core machine is shared, so single runs wander.
BENCHMARK(BM_CompileOneGraph)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true);

void BM_CompileGraphSet(benchmark::State& state) {
  const auto graphs = testing::generateGraphSet(static_cast<std::size_t>(state.range(0)),
                                                static_cast<std::size_t>(state.range(1)), 1);
  testing::testNodeLibrary();
  for (auto _ : state) {
    for (const auto& graph : graphs)
      compileOrFail(state, graph);
  }
}
BENCHMARK(BM_CompileGraphSet)
    ->Args({100, 100})
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true);

void BM_LoadTestNodeLibrary(benchmark::State& state) {
  compiler::Diagnostics sourceDiagnostics;
  const auto files =
      *nodes::nodeLibrarySources(testing::testNodeLibraryDirectory(), sourceDiagnostics);
  for (auto _ : state) {
    compiler::Diagnostics diagnostics;
    auto library = compiler::NodeLibrary::load(files, diagnostics);
    if (diagnostics.hasErrors())
      state.SkipWithError("the test node library has errors");
    benchmark::DoNotOptimize(library.nodeTypes().data());
  }
}
BENCHMARK(BM_LoadTestNodeLibrary)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true);

// The real library (nodes/), as every run of `memograph` loads it.
void BM_LoadEmbeddedNodeLibrary(benchmark::State& state) {
  compiler::Diagnostics sourceDiagnostics;
  const auto files = *nodes::nodeLibrarySources("", sourceDiagnostics);
  for (auto _ : state) {
    compiler::Diagnostics diagnostics;
    auto library = compiler::NodeLibrary::load(files, diagnostics);
    if (diagnostics.hasErrors())
      state.SkipWithError("the node library has errors");
    benchmark::DoNotOptimize(library.nodeTypes().data());
  }
}
BENCHMARK(BM_LoadEmbeddedNodeLibrary)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true);

// Parse time per megabyte of graph text (the SetBytesProcessed rate), for a dense valid
// graph (a chain of two-input nodes) and for a megabyte of numbers on one node, which the
// parser refuses at its value limit.
std::string denseChain(std::size_t bytes) {
  std::string text = "Float1Constant 0.5 Out>0;\n";
  for (std::size_t i = 0; text.size() < bytes; ++i) {
    const std::string id = std::to_string(i);
    text += "Add A<" + id + " B<" + id + " Out>" + std::to_string(i + 1) + ";\n";
  }
  return text;
}

void BM_ParseGraphPerMegabyte(benchmark::State& state) {
  const std::size_t bytes = static_cast<std::size_t>(state.range(0)) << 20;
  std::string text = "Float1Constant ";
  if (state.range(1) == 0) {
    text = denseChain(bytes);
  } else {
    for (std::size_t i = 0; text.size() < bytes; ++i)
      text += "1 ";
    text += "Out>0;\n";
  }
  const compiler::SourceFile file{"dense.mgraph", std::move(text)};
  for (auto _ : state) {
    compiler::Diagnostics diagnostics;
    auto graph = compiler::parseGraph(file, diagnostics);
    benchmark::DoNotOptimize(graph.nodes.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * file.text.size()));
}
// {MiB, 0 = dense chain / 1 = one node of numbers}
BENCHMARK(BM_ParseGraphPerMegabyte)
    ->Args({1, 0})
    ->Args({8, 0})
    ->Args({8, 1})
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
