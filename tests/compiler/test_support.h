// Helpers shared by the compiler tests: the two node libraries and one-call compilation.
#pragma once

#include <optional>
#include <string>

#include "compiler/compiler.h"
#include "compiler/node_library.h"

namespace memograph::testing {

// tests/compiler/testdata/nodes: small and stable, for golden files and inference tests.
const compiler::NodeLibrary& testLibrary();
// The real library (nodes/), as embedded in the binaries.
const compiler::NodeLibrary& realLibrary();

struct CompileRun {
  std::optional<compiler::CompiledMaterial> material;
  compiler::Diagnostics diagnostics;
  std::string messages() const { return compiler::formatDiagnostics(diagnostics); }
};

CompileRun compileText(const std::string& text,
                       const compiler::NodeLibrary& library = testLibrary(),
                       const std::string& path = "test.mgraph");

std::string readTextFile(const std::string& path);

// Loads a library from in-memory files, for the loader's own tests.
struct LibraryRun {
  compiler::NodeLibrary library;
  compiler::Diagnostics diagnostics;
};
LibraryRun loadLibrary(const std::vector<compiler::SourceFile>& files);

}  // namespace memograph::testing
