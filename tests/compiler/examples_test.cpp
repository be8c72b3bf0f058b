// Every bundled example graph compiles with the real node library, and glslang accepts the
// GLSL and HLSL it produces; the broken examples fail with a diagnostic.
#include <gtest/gtest.h>

#include <filesystem>

#include "glslang_check.h"
#include "test_support.h"

namespace memograph {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> graphsIn(const std::string& directory) {
  std::vector<std::string> paths;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    if (entry.path().extension() == ".mgraph")
      paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

TEST(Examples, ThereAreAtLeastTwelve) {
  EXPECT_GE(graphsIn(std::string(MEMOGRAPH_EXAMPLES_DIR) + "/graphs").size(), 12u);
}

TEST(Examples, EveryGraphCompilesAndGlslangAcceptsBothTargets) {
  std::vector<std::string> glsl, hlsl, names;
  const auto paths = graphsIn(std::string(MEMOGRAPH_EXAMPLES_DIR) + "/graphs");
  ASSERT_FALSE(paths.empty());
  for (const auto& path : paths) {
    SCOPED_TRACE(path);
    const auto run =
        testing::compileText(testing::readTextFile(path), testing::realLibrary(), path);
    ASSERT_TRUE(run.material) << run.messages();
    const auto& m = *run.material;
    const auto glslCheck = testing::compileGlslMaterials({m.glsl}, {m.metadata.name});
    EXPECT_TRUE(glslCheck.ok) << glslCheck.log;
    const auto hlslCheck = testing::compileHlslMaterials({m.hlsl}, {m.metadata.name});
    EXPECT_TRUE(hlslCheck.ok) << hlslCheck.log;
    glsl.push_back(m.glsl);
    hlsl.push_back(m.hlsl);
    names.push_back(m.metadata.name);
  }
  // All examples linked into one shader, as the renderer does.
  const auto glslAll = testing::compileGlslMaterials(glsl, names);
  EXPECT_TRUE(glslAll.ok) << glslAll.log;
  const auto hlslAll = testing::compileHlslMaterials(hlsl, names);
  EXPECT_TRUE(hlslAll.ok) << hlslAll.log;
}

TEST(Examples, BrokenGraphsFailWithADiagnosticInTheirFile) {
  const auto paths = graphsIn(std::string(MEMOGRAPH_EXAMPLES_DIR) + "/graphs/bad");
  ASSERT_FALSE(paths.empty());
  for (const auto& path : paths) {
    SCOPED_TRACE(path);
    const auto run =
        testing::compileText(testing::readTextFile(path), testing::realLibrary(), path);
    EXPECT_FALSE(run.material);
    ASSERT_TRUE(run.diagnostics.hasErrors());
    EXPECT_EQ(run.diagnostics.all().front().file, path);
    EXPECT_GT(run.diagnostics.all().front().location.line, 0u) << run.messages();
  }
}

}  // namespace
}  // namespace memograph
