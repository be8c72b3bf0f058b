// Every generated material graph of the built-in scenes goes through the real compiler:
// it must compile for both targets and be cacheable (reads no input but the UV).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compiler/compiler.h"
#include "compiler/node_library.h"
#include "memograph/embedded_node_library.h"
#include "runtime/scenes/builtin_scenes.h"

namespace memograph::runtime {
namespace {

namespace fs = std::filesystem;

// The embedded library, or the folder named by MEMOGRAPH_NODES_DIR (to test against a
// node library that is not built in yet).
std::vector<compiler::SourceFile> nodeLibraryFiles() {
  std::vector<compiler::SourceFile> files;
  if (const char* dir = std::getenv("MEMOGRAPH_NODES_DIR"); dir && *dir) {
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".inc")
        continue;
      std::ifstream in(entry.path());
      std::ostringstream text;
      text << in.rdbuf();
      files.push_back({fs::relative(entry.path(), dir).generic_string(), text.str()});
    }
    return files;
  }
  for (const auto& embedded : nodes::embeddedNodeLibrary()) {
    files.push_back({std::string(embedded.path), std::string(embedded.text)});
  }
  return files;
}

void expectAllCompile(const Scene& scene) {
  compiler::Diagnostics libraryDiagnostics;
  const compiler::NodeLibrary library =
      compiler::NodeLibrary::load(nodeLibraryFiles(), libraryDiagnostics);
  ASSERT_FALSE(libraryDiagnostics.hasErrors()) << compiler::formatDiagnostics(libraryDiagnostics);
  for (const char* node : {"NoiseTexture", "VoronoiTexture", "CheckerTexture", "BrickTexture"}) {
    if (!library.find(node)) {
      GTEST_SKIP() << "the node library has no " << node
                   << " yet (set MEMOGRAPH_NODES_DIR to a library that has)";
    }
  }
  for (const MaterialRef& material : scene.materials) {
    SCOPED_TRACE(material.name);
    compiler::Diagnostics diagnostics;
    const auto compiled = compiler::compileMaterial(
        compiler::SourceFile{material.name + ".mgraph", material.graphText}, library, {},
        diagnostics);
    EXPECT_TRUE(compiled.has_value()) << compiler::formatDiagnostics(diagnostics);
    if (!compiled)
      continue;
    EXPECT_EQ(compiled->metadata.name, material.name);
    EXPECT_FALSE(compiled->glsl.empty());
    EXPECT_FALSE(compiled->hlsl.empty());
    // Cacheable: the memoization benchmarks (issue 4) rely on every material using the cache.
    EXPECT_TRUE(compiled->metadata.cacheable);
    for (const std::string& input : compiled->metadata.inputsUsed)
      EXPECT_EQ(input, "uv");
  }
}

TEST(BuiltinMaterials, EveryClassroomGraphCompilesAndIsCacheable) {
  expectAllCompile(makeBuiltinScene("classroom"));
}

TEST(BuiltinMaterials, EveryLandscapeGraphCompilesAndIsCacheable) {
  BuiltinSceneOptions options;
  options.terrainCells = 8;
  expectAllCompile(makeBuiltinScene("landscape", options));
}

TEST(BuiltinMaterials, HeaviestSettingStillCompiles) {
  BuiltinSceneOptions options;
  options.materialCost = {16, 16};
  options.terrainCells = 8;
  expectAllCompile(makeBuiltinScene("landscape", options));
}

}  // namespace
}  // namespace memograph::runtime
