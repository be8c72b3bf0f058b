// Every generated material graph of the built-in scenes goes through the real compiler:
// it must compile for both targets and be cacheable (reads no input but the UV).
#include <gtest/gtest.h>

#include <cstdlib>

#include "compiler/compiler.h"
#include "compiler/node_library.h"
#include "memograph/node_library_loader.h"
#include "runtime/scene/builtin/builtin_scenes.h"

namespace memograph::runtime {
namespace {

void expectAllCompile(const Scene& scene) {
  // The embedded library, or the folder named by MEMOGRAPH_NODES_DIR (to test against a
  // node library that is not built in yet).
  const char* directory = std::getenv("MEMOGRAPH_NODES_DIR");
  compiler::Diagnostics libraryDiagnostics;
  const auto loaded = nodes::loadNodeLibrary(directory ? directory : "", libraryDiagnostics);
  ASSERT_TRUE(loaded) << compiler::formatDiagnostics(libraryDiagnostics);
  const compiler::NodeLibrary& library = *loaded;
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
    // Cacheable: the memoization benchmarks rely on every material using the cache.
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
