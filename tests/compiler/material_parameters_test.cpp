// Float constants as parameters (CompileOptions::parameterConstants) and a graph's shape
// (CompiledMaterial::shape), which the runtime's material instances are built on
// (docs/design/wavefront.md#material-instances).
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "compiler/compiler.h"
#include "glslang_check.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

// Scaled UVs sample a texture (the constant 4.0 then carries derivatives); a Pick's int Mode
// stays a literal.
std::string graph(double scale, double offset, int mode) {
  return "material Params;\nUVInput UV>1;\nMul A<1 B=" + std::to_string(scale) +
         " Out>2;\nImageTexture \"textures/wood.png\" UV<2 Color>3;\n"
         "Pick Mode=" +
         std::to_string(mode) + " A=(0.1, 0.2, " + std::to_string(offset) +
         ") B<3 Out>4;\nBaseColorOutput Color<4;\nAdd A<1 B=0.5 Out>5;\nWave In<5 Out>6;\n"
         "RoughnessOutput Roughness<6;\n";
}

std::optional<CompiledMaterial> compile(const std::string& text, const CompileOptions& options) {
  SourceFile file;
  file.path = "params.mgraph";
  file.text = text;
  Diagnostics diagnostics;
  auto compiled = compileMaterial(file, testing::testLibrary(), options, diagnostics);
  EXPECT_TRUE(compiled) << formatDiagnostics(diagnostics);
  return compiled;
}

// The distinct floats of the block the code reads (the whole function and a cut's functions
// read the same ones).
std::size_t parameterReads(const std::string& code) {
  const std::regex read("MG_MATERIAL_PARAMETER\\((\\d+)\\)");
  std::set<std::string> floats;
  for (auto it = std::sregex_iterator(code.begin(), code.end(), read); it != std::sregex_iterator();
       ++it)
    floats.insert((*it)[1]);
  return floats.size();
}

TEST(MaterialParameters, ChosenConstantsAreReadFromTheBlockInBothTargets) {
  CompileOptions options;
  const auto plain = compile(graph(4.0, 0.3, 1), options);
  ASSERT_TRUE(plain);
  // Mul's B, Pick's A, Add's B, each as wide as its socket; Mode is an int.
  ASSERT_EQ(plain->floatConstants.size(), 3u);
  EXPECT_EQ(plain->floatConstants[1], (std::vector<float>{0.1f, 0.2f, 0.3f}));
  EXPECT_EQ(parameterReads(plain->glsl), 0u);

  options.parameterConstants = {true, true, false};
  const auto parameters = compile(graph(4.0, 0.3, 1), options);
  ASSERT_TRUE(parameters);
  const std::size_t floats = plain->floatConstants[0].size() + plain->floatConstants[1].size();
  EXPECT_EQ(parameterReads(parameters->glsl), floats);
  EXPECT_EQ(parameterReads(parameters->hlsl), floats);
  // The last one read is float floats - 1 of the block; Add's B stays a literal.
  EXPECT_NE(parameters->glsl.find("MG_MATERIAL_PARAMETER(" + std::to_string(floats - 1) + ")"),
            std::string::npos);
  EXPECT_EQ(parameters->glsl.find("MG_MATERIAL_PARAMETER(" + std::to_string(floats) + ")"),
            std::string::npos);
  // glslang takes both targets with the block's reads defined as the including shader would.
  const std::string read = "#define MG_MATERIAL_PARAMETER(k) (0.25 + float(k))\n";
  const auto glsl = testing::compileGlslMaterials({read + parameters->glsl}, {"Params"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
  const auto hlsl = testing::compileHlslMaterials({read + parameters->hlsl}, {"Params"});
  EXPECT_TRUE(hlsl.ok) << hlsl.log;
}

TEST(MaterialParameters, GraphsDifferingOnlyInFloatConstantsShareAShape) {
  CompileOptions options;
  options.reportShape = true;
  const auto a = compile(graph(4.0, 0.3, 1), options);
  const auto b = compile(graph(9.5, 0.7, 1), options);
  const auto otherMode = compile(graph(4.0, 0.3, 0), options);
  ASSERT_TRUE(a && b && otherMode);
  EXPECT_FALSE(a->shape.empty());
  EXPECT_EQ(a->shape, b->shape);
  EXPECT_NE(a->shape, otherMode->shape);                  // an int setting is part of the shape
  EXPECT_EQ(a->shape.find("Params"), std::string::npos);  // nor is the name
  std::size_t floats = 0;
  for (const auto& constant : a->floatConstants)
    floats += constant.size();
  EXPECT_EQ(parameterReads(a->shape), floats);
}

}  // namespace
}  // namespace memograph::compiler
