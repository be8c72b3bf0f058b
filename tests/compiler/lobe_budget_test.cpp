// The lobe budget (compiler/lobe_budget.*): a graph whose sinks could add more lobes than a
// hit holds, or write two sets of Principled outputs at one hit, is refused with a message
// instead of losing a lobe in mg_addLobe; ChooseShader's sides count the larger of the two.
// ChooseShader's number is per hit: never in a cache entry.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "compiler/lobe_budget.h"
#include "compiler/variation.h"
#include "glslang_check.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::compileText;
using memograph::testing::realLibrary;

TEST(LobeBudget, FiveSinksAtEveryHitAreRefused) {
  const auto run = compileText(
      "material Five;\n"
      "DiffuseBsdf;\nDiffuseBsdf Roughness=0.5;\nGlossyBsdf;\nVelvetBsdf;\nTranslucentBsdf;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
  EXPECT_NE(run.messages().find("can add 5 lobes at one hit, more than the 4"), std::string::npos)
      << run.messages();
  EXPECT_NE(run.messages().find("test.mgraph:6:1"), std::string::npos) << run.messages();
}

TEST(LobeBudget, TwoPrincipledBsdfsUnderAMixAreRefused) {
  const auto run = compileText(
      "material TwoSets;\n"
      "MixShader Fac=0.5 WeightA>1 WeightB>2;\n"
      "PrincipledBsdf Weight<1;\nPrincipledBsdf Metallic=1 Weight<2;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
  EXPECT_NE(run.messages().find("2 Principled BSDFs"), std::string::npos) << run.messages();
}

TEST(LobeBudget, TodaysLayeredPrincipledFits) {
  const auto run = compileText(
      "material Layered;\nPrincipledOutput CyclesPrincipled=1;\nPrincipledLayers Clearcoat=1;\n",
      realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
}

TEST(LobeBudget, AChoiceCountsItsLargerSide) {
  // Two Principled BSDFs with every layer: eight lobes and two sets, at most four and one at
  // a hit.
  const auto run = compileText(
      "material Chosen;\n"
      "MixShader Fac=0.3 WeightA>1 WeightB>2;\n"
      "ChooseShader WeightA<1 WeightB<2 ChosenA>3 ChosenB>4;\n"
      "PrincipledBsdf Layers=7 Weight<3;\nPrincipledBsdf Layers=7 Weight<4;\n",
      realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  // Nested: (a Principled of 3 lobes or one of 1) and, beside that choice, a Glass: 3 + 1;
  // with every layer 4 + 1, refused.
  const std::string nested =
      "MixShader Fac=0.4 WeightA>10 WeightB>11;\n"
      "MixShader Fac=0.35 Weight<10 WeightA>1 WeightB>2;\n"
      "ChooseShader WeightA<1 WeightB<2 Stream=1 ChosenA>3 ChosenB>4;\n"
      "GlassBsdf Weight<11;\n"
      "PrincipledBsdf Layers=0 Weight<4;\n";
  const auto fits = compileText(
      "material Nested;\n" + nested + "PrincipledBsdf Layers=3 Weight<3;\n", realLibrary());
  ASSERT_TRUE(fits.material) << fits.messages();
  const auto overflows = compileText(
      "material Nested;\n" + nested + "PrincipledBsdf Layers=7 Weight<3;\n", realLibrary());
  EXPECT_FALSE(overflows.material);
  EXPECT_NE(overflows.messages().find("can add 5 lobes"), std::string::npos)
      << overflows.messages();
}

TEST(LobeBudget, AWeightFromAnythingButMixAndChooseCountsAtEveryHit) {
  // ChosenA times a texture may be above 0 where B was chosen? No, but the pass does not look
  // through arithmetic: it counts the sink at every hit, never fewer times than it can run.
  const auto run = compileText(
      "material Scaled;\n"
      "ChooseShader WeightA=1 WeightB=1 ChosenA>1 ChosenB>2;\n"
      "Mul A<1 B=0.5 Out>5;\n"
      "PrincipledBsdf Layers=7 Weight<5;\nPrincipledBsdf Layers=0 Weight<2;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
}

TEST(LobeBudget, ChooseShaderIsPerHitAndCompilesForBothTargets) {
  EXPECT_EQ(inputVariation("closureSeed"), Variation::PerHit);
  const auto run = compileText(
      "material Choice;\n"
      "UVInput Out>7;\n"
      "NoiseTexture Vector<7 Fac>8;\n"
      "MixShader Fac<8 WeightA>1 WeightB>2;\n"
      "ChooseShader WeightA<1 WeightB<2 ChosenA>3 ChosenB>4;\n"
      "PrincipledBsdf BaseColor=(0.8, 0.1, 0.1) Layers=2 Clearcoat=1 Weight<3;\n"
      "PrincipledBsdf Metallic=1 Weight<4;\n",
      realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  const CompiledMaterial& m = *run.material;
  // The choice is never cached: the material is not whole-output cacheable, and its cut (the
  // noise) holds no ChooseShader.
  EXPECT_FALSE(m.metadata.cacheable);
  const auto& inputs = m.metadata.inputsUsed;
  EXPECT_NE(std::find(inputs.begin(), inputs.end(), "closureSeed"), inputs.end());
  const std::size_t cut = m.glsl.find("void EvaluateMaterialCut_Choice(");
  ASSERT_NE(cut, std::string::npos) << m.glsl;
  const std::string cutText = m.glsl.substr(cut, m.glsl.find("\n}\n", cut) - cut);
  EXPECT_EQ(cutText.find("ChooseShader"), std::string::npos) << cutText;
  EXPECT_NE(cutText.find("NoiseTexture"), std::string::npos) << cutText;
  const auto glsl = memograph::testing::compileGlslMaterials({m.glsl}, {"Choice"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
  const auto hlsl = memograph::testing::compileHlslMaterials({m.hlsl}, {"Choice"});
  EXPECT_TRUE(hlsl.ok) << hlsl.log;
}

}  // namespace
}  // namespace memograph::compiler
