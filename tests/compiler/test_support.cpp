#include "test_support.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "memograph/node_library_loader.h"

namespace memograph::testing {

namespace {

compiler::NodeLibrary loadOrThrow(const std::string& directory) {
  compiler::Diagnostics diagnostics;
  auto library = nodes::loadNodeLibrary(directory, diagnostics);
  if (!library) {
    throw std::runtime_error("node library failed to load:\n" +
                             compiler::formatDiagnostics(diagnostics));
  }
  return std::move(*library);
}

}  // namespace

const compiler::NodeLibrary& testLibrary() {
  static const compiler::NodeLibrary library =
      loadOrThrow(std::string(MEMOGRAPH_TEST_DATA_DIR) + "/nodes");
  return library;
}

const compiler::NodeLibrary& realLibrary() {
  static const compiler::NodeLibrary library = loadOrThrow("");
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
