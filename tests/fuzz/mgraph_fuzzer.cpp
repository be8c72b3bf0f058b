// libFuzzer entry point: any bytes as a .mgraph file through the whole compiler (parse,
// resolve, schedule, infer, emit GLSL and HLSL; and the `check` report), with the test node
// library. Crashes, hangs, leaks and sanitizer reports are findings; so is a failed compile
// whose diagnostics do not point into the file. How to run it: docs/design/testing.md.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "compiler/compiler.h"
#include "graph_generator.h"

namespace {

using namespace memograph;

// An error must say where: a line of the file (1 … last line + 1, the end of input) and
// a column on it.
bool hasPositionedError(const compiler::Diagnostics& diagnostics,
                        const compiler::SourceFile& file) {
  std::uint32_t lines = 1;
  for (const char c : file.text)
    lines += c == '\n';
  for (const auto& d : diagnostics.all()) {
    if (d.severity == compiler::Severity::Error && d.location.line >= 1 &&
        d.location.line <= lines && d.location.column >= 1)
      return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const compiler::SourceFile file{"fuzz.mgraph",
                                  std::string(reinterpret_cast<const char*>(data), size)};
  compiler::Diagnostics diagnostics;
  const auto compiled =
      compiler::compileMaterial(file, testing::testNodeLibrary(), {}, diagnostics);
  const std::string printed = compiler::formatDiagnostics(diagnostics);
  if (!compiled && !hasPositionedError(diagnostics, file)) {
    std::fprintf(stderr, "compile failed without a positioned error:\n%s\n", printed.c_str());
    std::abort();
  }
  compiler::Diagnostics checkDiagnostics;
  const auto report = compiler::checkMaterial(file, testing::testNodeLibrary(), checkDiagnostics);
  if (report.has_value() != compiled.has_value()) {
    std::fputs("compileMaterial and checkMaterial disagree on this input\n", stderr);
    std::abort();
  }
  return 0;
}
