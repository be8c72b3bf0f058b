// Emission: golden files for representative graphs, byte-identical output, SSA form, and
// glslang accepting what is emitted for both targets.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>

#include "glslang_check.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::compileText;
using memograph::testing::readTextFile;

struct GoldenCase {
  const char* name;
  const char* graph;
};

constexpr GoldenCase kGoldenCases[] = {
    {"listing_5_1",
     "Mul A<0 B<1 Out>2;\nColorOutput In<3;\nAdd A<1 B<2 Out>3;\n"
     "Float1Constant 0.5 Out>1;\nNormalInput Out>0;\n"},
    {"derivatives",
     "# scaled UVs sample a texture (needs derivatives); a wave of them sets roughness\n"
     "UVInput UV>1;\nMul A<1 B=4.0 Out>2;\nImageTexture \"textures/wood.png\" UV<2 Color>3;\n"
     "BaseColorOutput Color<3;\nAdd A<1 B=0.5 Out>4;\nWave In<4 Out>5;\n"
     "RoughnessOutput Roughness<5;\n"},
    {"constants_and_helpers",
     "material Helpers;\nFloat3Constant 1 0.5 0.25 Out>1;\nWave In<1 Out>2;\n"
     "Pick Mode=1 A=(0.1, 0.2, 0.3) B<1 Out>3;\nBaseColorOutput Color<3;\n"
     "RoughnessOutput Roughness<2;\nEmissionOutput Color=(2, 2, 2);\n"},
};

std::string goldenPath(const std::string& file) {
  return std::string(MEMOGRAPH_TEST_DATA_DIR) + "/../golden/" + file;
}

// Set MEMOGRAPH_UPDATE_GOLDEN=1 to rewrite the golden files after an intended change.
void expectMatchesGolden(const std::string& actual, const std::string& file) {
  const std::string path = goldenPath(file);
  if (std::getenv("MEMOGRAPH_UPDATE_GOLDEN")) {
    std::ofstream(path, std::ios::binary) << actual;
    return;
  }
  std::string expected;
  try {
    expected = readTextFile(path);
  } catch (const std::exception&) {
    FAIL() << "missing golden file " << path << " (run with MEMOGRAPH_UPDATE_GOLDEN=1)";
  }
  EXPECT_EQ(actual, expected) << "generated code differs from " << path;
}

class Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, GlslHlslAndMetadataMatchTheGoldenFiles) {
  const auto& c = GetParam();
  const auto run = compileText(c.graph, testing::testLibrary(), std::string(c.name) + ".mgraph");
  ASSERT_TRUE(run.material) << run.messages();
  expectMatchesGolden(run.material->glsl, std::string(c.name) + ".glsl");
  expectMatchesGolden(run.material->hlsl, std::string(c.name) + ".hlsl");
  expectMatchesGolden(run.material->metadataJson, std::string(c.name) + ".json");
}

TEST_P(Golden, CompilesWithGlslangForBothTargets) {
  const auto& c = GetParam();
  const auto run = compileText(c.graph, testing::testLibrary(), std::string(c.name) + ".mgraph");
  ASSERT_TRUE(run.material) << run.messages();
  const auto glsl =
      testing::compileGlslMaterials({run.material->glsl}, {run.material->metadata.name});
  EXPECT_TRUE(glsl.ok) << glsl.log << run.material->glsl;
  const auto hlsl =
      testing::compileHlslMaterials({run.material->hlsl}, {run.material->metadata.name});
  EXPECT_TRUE(hlsl.ok) << hlsl.log << run.material->hlsl;
}

TEST_P(Golden, OutputIsByteIdenticalAcrossRuns) {
  const auto& c = GetParam();
  const auto first = compileText(c.graph);
  const auto second = compileText(c.graph);
  ASSERT_TRUE(first.material && second.material);
  EXPECT_EQ(first.material->glsl, second.material->glsl);
  EXPECT_EQ(first.material->hlsl, second.material->hlsl);
  EXPECT_EQ(first.material->metadataJson, second.material->metadataJson);
}

INSTANTIATE_TEST_SUITE_P(Cases, Golden, ::testing::ValuesIn(kGoldenCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Emitter, NodeOrderInTheFileDoesNotChangeTheOutput) {
  const auto a = compileText(
      "NormalInput Out>0;\nFloat1Constant 0.5 Out>1;\nMul A<0 B<1 Out>2;\n"
      "Add A<1 B<2 Out>3;\nColorOutput In<3;\n");
  const auto b = compileText(
      "ColorOutput In<3;\nAdd A<1 B<2 Out>3;\nMul A<0 B<1 Out>2;\n"
      "NormalInput Out>0;\nFloat1Constant 0.5 Out>1;\n");
  ASSERT_TRUE(a.material && b.material);
  EXPECT_EQ(a.material->glsl, b.material->glsl);
}

TEST(Emitter, EveryLinkVariableIsAssignedExactlyOnce) {
  const auto run = compileText(kGoldenCases[1].graph);
  ASSERT_TRUE(run.material);
  const std::string& code = run.material->glsl;
  // The whole-graph function alone: the cut and rest functions after it redeclare its links.
  const std::size_t start = code.find("void EvaluateMaterial_");
  const std::string body = code.substr(start, code.find("\n}\n", start) - start);
  // Each link appears as the last argument (the out parameter) of exactly one call.
  std::set<std::string> declared;
  const std::regex declaration(R"(\n  \w+ (link\d+);)");
  for (std::sregex_iterator it(body.begin(), body.end(), declaration), end; it != end; ++it) {
    EXPECT_TRUE(declared.insert((*it)[1]).second) << "declared twice: " << (*it)[1];
  }
  EXPECT_EQ(declared.size(), 5u);
  for (const auto& link : declared) {
    const std::regex assigned(", " + link + R"(\);)");
    const auto count = std::distance(std::sregex_iterator(body.begin(), body.end(), assigned),
                                     std::sregex_iterator());
    EXPECT_EQ(count, 1) << link;
  }
}

TEST(Emitter, OnlyTheFunctionsAMaterialUsesAreEmitted) {
  const auto run = compileText("NormalInput Out>1;\nColorOutput In<1;\n");
  ASSERT_TRUE(run.material);
  EXPECT_EQ(run.material->glsl.find("void Mul("), std::string::npos);
  EXPECT_EQ(run.material->glsl.find("mg_wave"), std::string::npos);
  const auto helpers =
      compileText("NormalInput Out>1;\nWave In<1 Out>2;\nRoughnessOutput Roughness<2;\n");
  ASSERT_TRUE(helpers.material);
  const auto& code = helpers.material->glsl;
  // Callees come before their callers.
  EXPECT_LT(code.find("float mg_tri("), code.find("float mg_wave("));
  EXPECT_LT(code.find("float mg_wave("), code.find("void Wave("));
}

TEST(Emitter, SeveralMaterialsCoexistInOneShader) {
  std::vector<std::string> glsl, hlsl, names;
  for (const auto& c : kGoldenCases) {
    const auto run = compileText(c.graph, testing::testLibrary(), std::string(c.name) + ".mgraph");
    ASSERT_TRUE(run.material) << run.messages();
    glsl.push_back(run.material->glsl);
    hlsl.push_back(run.material->hlsl);
    names.push_back(run.material->metadata.name);
  }
  const auto glslCheck = testing::compileGlslMaterials(glsl, names);
  EXPECT_TRUE(glslCheck.ok) << glslCheck.log;
  const auto hlslCheck = testing::compileHlslMaterials(hlsl, names);
  EXPECT_TRUE(hlslCheck.ok) << hlslCheck.log;
}

std::string tableLiteral() {
  std::string table = "[";
  for (int i = 0; i < 256; ++i)
    table += std::to_string(i) + " 0.5 0 1\n";
  return table + "]";
}

TEST(Emitter, TableLiteralsBecomeLocalsFilledEntryByEntryForBothTargets) {
  const auto run =
      compileText("UVInput UV>1;\nSquash In<1 Out>2;\nRampLookup Fac<2 Ramp=" + tableLiteral() +
                  " Color>3;\nBaseColorOutput Color<3;\n");
  ASSERT_TRUE(run.material) << run.messages();
  const auto& glsl = run.material->glsl;
  EXPECT_NE(glsl.find("Table table2_Ramp;"), std::string::npos);
  EXPECT_NE(glsl.find("table2_Ramp.v[255] = float4(255.0, 0.5, 0.0, 1.0);"), std::string::npos);
  EXPECT_NE(glsl.find("RampLookup(link2, table2_Ramp, link3);"), std::string::npos);
  const auto glslCheck = testing::compileGlslMaterials({glsl}, {run.material->metadata.name});
  EXPECT_TRUE(glslCheck.ok) << glslCheck.log;
  const auto hlslCheck =
      testing::compileHlslMaterials({run.material->hlsl}, {run.material->metadata.name});
  EXPECT_TRUE(hlslCheck.ok) << hlslCheck.log;
}

TEST(Emitter, TableSocketsTakeOnlyTablesAndTablesOnlyTableSockets) {
  const auto number =
      compileText("RampLookup Fac=0.5 Ramp=1.0 Color>3;\nBaseColorOutput Color<3;\n");
  EXPECT_FALSE(number.material);
  EXPECT_NE(number.messages().find("takes a table: [ 1024 numbers ]"), std::string::npos)
      << number.messages();
  const auto misplaced =
      compileText("RampLookup Fac=" + tableLiteral() + " Ramp=" + tableLiteral() +
                  " Color>3;\nBaseColorOutput Color<3;\n");
  EXPECT_FALSE(misplaced.material);
  EXPECT_NE(misplaced.messages().find("does not take a [table]"), std::string::npos)
      << misplaced.messages();
}

TEST(Emitter, GlslangCheckCanFail) {
  const auto broken =
      testing::compileGlslMaterials({"void EvaluateMaterial_X(int) { oops; }"}, {"X"});
  EXPECT_FALSE(broken.ok);
}

TEST(Metadata, CacheableOnlyWhenOutputsDependOnUvAndConstants) {
  const auto uvOnly = compileText(
      "UVInput UV>1;\nImageTexture \"a.png\" UV<1 Color>2;\n"
      "BaseColorOutput Color<2;\n");
  ASSERT_TRUE(uvOnly.material) << uvOnly.messages();
  EXPECT_TRUE(uvOnly.material->metadata.cacheable);
  EXPECT_EQ(uvOnly.material->metadata.inputsUsed, std::vector<std::string>{"uv"});
  EXPECT_EQ(uvOnly.material->metadata.textures, std::vector<std::string>{"a.png"});
  const auto withTime = compileText("TimeInput Out>1;\nRoughnessOutput Roughness<1;\n");
  ASSERT_TRUE(withTime.material);
  EXPECT_FALSE(withTime.material->metadata.cacheable);
  const auto constantOnly = compileText("RoughnessOutput Roughness=0.25;\n");
  ASSERT_TRUE(constantOnly.material);
  EXPECT_TRUE(constantOnly.material->metadata.cacheable);
}

TEST(Metadata, TextureSlotsFollowFirstMentionAndShareRepeatedPaths) {
  const auto run = compileText(
      "UVInput UV>1;\nImageTexture \"b.png\" UV<1 Color>2;\nImageTexture \"a.png\" UV<1 Color>3;\n"
      "ImageTexture \"b.png\" UV<1 Color>4;\nAdd A<2 B<3 Out>5;\nAdd A<5 B<4 Out>6;\n"
      "BaseColorOutput Color<6;\n");
  ASSERT_TRUE(run.material) << run.messages();
  EXPECT_EQ(run.material->metadata.textures, (std::vector<std::string>{"b.png", "a.png"}));
}

}  // namespace
}  // namespace memograph::compiler
