// A generated include carries only the prelude helpers and node functions
// its material reaches (docs/guide/nodes.md), yet any number of includes, and the whole
// prelude before them, still make one valid shader.
#include <gtest/gtest.h>

#include "glslang_check.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::compileGlslMaterials;
using memograph::testing::compileHlslMaterials;
using memograph::testing::compileText;
using memograph::testing::realLibrary;

constexpr const char* kSmall =
    "material Small;\nUVInput Out>1;\nMul A<1 B=2 Out>2;\nBaseColorOutput In<2;\n";
constexpr const char* kNoisy =
    "material Noisy;\nUVInput Out>1;\nNoiseTexture Vector<1 Fac>2;\n"
    "ImageTexture \"a.png\" UV<1 Color>3;\nMix A<3 B=(0,0,0) Factor<2 Out>4;\n"
    "BaseColorOutput In<4;\n";

TEST(LeanEmission, AnIncludeCarriesOnlyThePreludeFunctionsItReaches) {
  const auto run = compileText(kSmall, realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  for (const std::string& code : {run.material->glsl, run.material->hlsl}) {
    // Always: the types and the interface.
    EXPECT_NE(code.find("struct float3_D"), std::string::npos);
    EXPECT_NE(code.find("struct Table"), std::string::npos);
    EXPECT_NE(code.find("struct MaterialInputs"), std::string::npos);
    EXPECT_NE(code.find("struct MaterialOutputs"), std::string::npos);
    EXPECT_NE(code.find("mg_SampleTexture(int textureIndex"), std::string::npos);
    // Reached: the function body's own call and the conversion it needs.
    EXPECT_NE(code.find("MaterialOutputs mg_defaultMaterialOutputs("), std::string::npos);
    EXPECT_NE(code.find("float3 mg_to_float3(float2 a)"), std::string::npos);
    // Not reached: hashing, noise, derivative arithmetic.
    EXPECT_EQ(code.find("mg_pcg"), std::string::npos);
    EXPECT_EQ(code.find("mg_smoothstep"), std::string::npos);
    EXPECT_EQ(code.find("float3_D mg_mul("), std::string::npos);
    // The interface's declarations are most of it: MaterialInputs with its traced inputs,
    // objectNormal and generatedScale, MaterialOutputs with its BSDF lobes, their default and
    // the lobe kinds with the Principled layers' and the Sharp distribution's mark (14,321
    // bytes of GLSL, 13,883 of HLSL).
    EXPECT_LT(code.size(), 14'500u) << "the whole prelude is ~56 KB";
  }
  EXPECT_NE(run.material->glsl.find("#define float3 vec3"), std::string::npos);
  EXPECT_EQ(run.material->hlsl.find("#define float3 vec3"), std::string::npos);
}

TEST(LeanEmission, PreludeFunctionsComeFirstInDefinitionOrderEachGuarded) {
  const auto run = compileText(kNoisy, realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  const std::string& code = run.material->glsl;
  // The prelude's functions precede the families' (Mix needs the prelude's mg_mix), in
  // definition order (mg_saturate is defined before mg_mix), each under its guard.
  const auto saturate = code.find("float mg_saturate(float a)");
  const auto mix = code.find("float3 mg_mix(float3 a, float3 b, float t)");
  const auto node = code.find("void Mix(");
  // NoiseTexture's Dimensions is its default, a constant: the call goes to the
  // specialisation for it.
  const auto noise = code.find("void mg_spec_NoiseTexture_Dimensions_2(");
  ASSERT_NE(saturate, std::string::npos);
  ASSERT_NE(mix, std::string::npos);
  ASSERT_NE(node, std::string::npos);
  ASSERT_NE(noise, std::string::npos);
  EXPECT_LT(saturate, mix);
  EXPECT_LT(mix, node);
  EXPECT_LT(mix, noise);
  EXPECT_NE(code.find("#ifndef MG_FN_mg_mix_float3_float3_float\n#define "
                      "MG_FN_mg_mix_float3_float3_float\n"),
            std::string::npos);
  // The plain Mix calls no derivative overload of mg_mix.
  EXPECT_EQ(code.find("float3_D mg_mix("), std::string::npos);
  // Deterministic.
  EXPECT_EQ(compileText(kNoisy, realLibrary()).material->glsl, code);
}

// A node called with a constant enum goes to the library's specialisation for that value
// (docs/guide/nodes.md, "Specialisations"), so that the shader compilers never see the
// node's other variants; a linked value keeps the node and all of them. Both compile.
TEST(LeanEmission, AConstantEnumCallsTheNodesSpecialisation) {
  const char* constant =
      "material Constant;\nUVInput Out>1;\nNoiseTexture Vector<1 Dimensions=1 Fac>2;\n"
      "BaseColorOutput In<2;\n";
  const char* linked =
      "material Linked;\nUVInput Out>1;\nIntConstant Value=1 Out>3;\n"
      "NoiseTexture Vector<1 Dimensions<3 Fac>2;\nBaseColorOutput In<2;\n";
  const auto special = compileText(constant, realLibrary());
  const auto general = compileText(linked, realLibrary());
  ASSERT_TRUE(special.material && general.material) << special.messages() << general.messages();
  for (const std::string& code : {special.material->glsl, special.material->hlsl}) {
    EXPECT_NE(code.find("  mg_spec_NoiseTexture_Dimensions_1(mg_to_float3(link1)"),
              std::string::npos)
        << code;
    EXPECT_EQ(code.find("void NoiseTexture("), std::string::npos);
    EXPECT_EQ(code.find("mg_cy_noise_texture3("), std::string::npos) << "another variant";
    EXPECT_NE(code.find("mg_cy_noise_texture2("), std::string::npos);
  }
  for (const std::string& code : {general.material->glsl, general.material->hlsl}) {
    EXPECT_NE(code.find("  NoiseTexture(mg_to_float3(link1)"), std::string::npos) << code;
    EXPECT_EQ(code.find("mg_spec_NoiseTexture"), std::string::npos);
    EXPECT_NE(code.find("mg_cy_noise_texture3("), std::string::npos);
  }
  // Voronoi's enum sockets come first (Feature, Metric) without specialisations: the first
  // that has one, Dimensions, is the one specialised, with and without derivatives.
  const char* voronoi =
      "material Cells;\nUVInput Out>1;\nVoronoiTexture Vector<1 Dimensions=1 Distance>2 "
      "Color>4;\nImageTexture \"a.png\" UV<4 Color>3;\nMix A<3 B=(0,0,0) Factor<2 Out>5;\n"
      "BaseColorOutput In<5;\n";
  const auto cells = compileText(voronoi, realLibrary());
  ASSERT_TRUE(cells.material) << cells.messages();
  EXPECT_NE(
      cells.material->glsl.find("  mg_spec_VoronoiTexture_Dimensions_1(link1, 5.0, 1.0, 0, 0,"),
      std::string::npos)
      << cells.material->glsl;
  EXPECT_NE(cells.material->glsl.find("void mg_spec_VoronoiTexture_Dimensions_1(in float2_D"),
            std::string::npos);
  EXPECT_EQ(cells.material->glsl.find("void mg_voronoi("), std::string::npos);
  EXPECT_EQ(cells.material->glsl.find("void mg_voronoi_D("), std::string::npos);
  auto glsl =
      compileGlslMaterials({special.material->glsl, general.material->glsl, cells.material->glsl},
                           {"Constant", "Linked", "Cells"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
  auto hlsl =
      compileHlslMaterials({special.material->hlsl, general.material->hlsl, cells.material->hlsl},
                           {"Constant", "Linked", "Cells"});
  EXPECT_TRUE(hlsl.ok) << hlsl.log;
}

TEST(LeanEmission, SeveralLeanIncludesAndTheWholePreludeShareOneShader) {
  const auto small = compileText(kSmall, realLibrary());
  const auto noisy = compileText(kNoisy, realLibrary());
  ASSERT_TRUE(small.material && noisy.material) << small.messages() << noisy.messages();
  // Two materials reaching different, overlapping sets of prelude functions.
  auto glsl =
      compileGlslMaterials({small.material->glsl, noisy.material->glsl}, {"Small", "Noisy"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
  auto hlsl =
      compileHlslMaterials({small.material->hlsl, noisy.material->hlsl}, {"Small", "Noisy"});
  EXPECT_TRUE(hlsl.ok) << hlsl.log;
  // The renderer's callable path: the whole prelude under the emitter's guard (the material
  // linker's preludeSource), then a material include.
  const std::string whole = "#ifndef MG_PRELUDE_GLSL\n#define MG_PRELUDE_GLSL\n" +
                            realLibrary().prelude(Target::Glsl) + "#endif\n";
  glsl = compileGlslMaterials({whole + noisy.material->glsl, small.material->glsl},
                              {"Noisy", "Small"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
}

TEST(LeanEmission, TheLoaderLinksPreludeFunctionsLikeHelpers) {
  const auto& library = realLibrary();
  const auto& functions = library.functions();
  const auto& muls = library.functionsNamed("mg_mul");
  ASSERT_GT(muls.size(), 4u);
  for (const std::size_t index : muls) {
    EXPECT_TRUE(functions[index].prelude);
    // Its own name: only the overloads defined before it.
    for (const std::size_t callee : functions[index].callees) {
      if (functions[callee].name == "mg_mul") {
        EXPECT_LT(callee, index);
      }
    }
  }
  // Target-specific functions (GLSL's fmod) are for one target only.
  const auto& fmods = library.functionsNamed("fmod");
  ASSERT_FALSE(fmods.empty());
  for (const std::size_t index : fmods) {
    EXPECT_TRUE(functions[index].isFor(Target::Glsl));
    EXPECT_FALSE(functions[index].isFor(Target::Hlsl));
  }
  // A node reaches prelude functions through its callees.
  const NodeType* mix = library.find("Mix");
  ASSERT_NE(mix, nullptr);
  std::vector<std::size_t> stack{mix->overloads[0].function};
  std::vector<char> seen(functions.size(), 0);
  bool reachesMix = false;
  while (!stack.empty()) {
    const std::size_t f = stack.back();
    stack.pop_back();
    if (seen[f]++)
      continue;
    reachesMix = reachesMix || (functions[f].name == "mg_mix" && functions[f].prelude);
    for (const std::size_t callee : functions[f].callees)
      stack.push_back(callee);
  }
  EXPECT_TRUE(reachesMix);
}

}  // namespace
}  // namespace memograph::compiler
