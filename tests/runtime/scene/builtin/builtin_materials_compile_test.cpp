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

// ao=N and bevel=N (the traced-inputs benchmark's scenes, tools/bench/wavefront_floor_device.sh
// --traced-inputs): every recipe's graph compiles with an Ambient Occlusion node of N samples
// on its base colour and a Bevel node of N samples as its normal, recorded in the metadata;
// the emitters and the mirror keep their constants.
TEST(BuiltinMaterials, TracedInputKnobsPutAmbientOcclusionAndBevelInTheRecipes) {
  BuiltinSceneOptions options;
  options.terrainCells = 8;
  options.materialCost.ambientOcclusionSamples = 8;
  options.materialCost.bevelSamples = 4;
  const Scene scene = makeBuiltinScene("landscape", options);
  compiler::Diagnostics libraryDiagnostics;
  const auto library = nodes::loadNodeLibrary("", libraryDiagnostics);
  ASSERT_TRUE(library) << compiler::formatDiagnostics(libraryDiagnostics);
  int traced = 0;
  for (const MaterialRef& material : scene.materials) {
    SCOPED_TRACE(material.name);
    compiler::Diagnostics diagnostics;
    const auto compiled = compiler::compileMaterial(
        compiler::SourceFile{material.name + ".mgraph", material.graphText}, *library, {},
        diagnostics);
    ASSERT_TRUE(compiled.has_value()) << compiler::formatDiagnostics(diagnostics);
    if (!compiled->metadata.ambientOcclusion)
      continue;
    ++traced;
    EXPECT_EQ(compiled->metadata.ambientOcclusion->samples, 8u);
    ASSERT_TRUE(compiled->metadata.bevel.has_value());
    EXPECT_EQ(compiled->metadata.bevel->samples, 4u);
    EXPECT_FALSE(compiled->metadata.cacheable);  // per hit (traced-inputs.md)
  }
  EXPECT_EQ(traced, static_cast<int>(scene.materials.size()));
}

}  // namespace
}  // namespace memograph::runtime
