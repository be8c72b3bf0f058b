#include "test_support.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "compiler/library_files.h"
#include "memograph/embedded_node_library.h"

namespace memograph::testing {

namespace {

compiler::NodeLibrary loadOrThrow(const std::vector<compiler::SourceFile>& files) {
  compiler::Diagnostics diagnostics;
  auto library = compiler::NodeLibrary::load(files, diagnostics);
  if (diagnostics.hasErrors()) {
    throw std::runtime_error("node library failed to load:\n" +
                             compiler::formatDiagnostics(diagnostics));
  }
  return library;
}

}  // namespace

const compiler::NodeLibrary& testLibrary() {
  static const compiler::NodeLibrary library = [] {
    compiler::Diagnostics diagnostics;
    const auto files = compiler::readNodeLibraryDirectory(
        std::string(MEMOGRAPH_TEST_DATA_DIR) + "/nodes", diagnostics);
    if (!files)
      throw std::runtime_error(compiler::formatDiagnostics(diagnostics));
    return loadOrThrow(*files);
  }();
  return library;
}

const compiler::NodeLibrary& realLibrary() {
  static const compiler::NodeLibrary library = [] {
    std::vector<compiler::SourceFile> files;
    for (const auto& f : nodes::embeddedNodeLibrary()) {
      files.push_back({std::string(f.path), std::string(f.text)});
    }
    return loadOrThrow(files);
  }();
  return library;
}

CompileRun compileText(const std::string& text, const compiler::NodeLibrary& library,
                       const std::string& path) {
  CompileRun run;
  run.material = compiler::compileMaterial({path, text}, library, {}, run.diagnostics);
  return run;
}

std::string readTextFile(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream)
    throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

LibraryRun loadLibrary(const std::vector<compiler::SourceFile>& files) {
  LibraryRun run;
  run.library = compiler::NodeLibrary::load(files, run.diagnostics);
  return run;
}

}  // namespace memograph::testing
