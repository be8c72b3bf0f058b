// Overload selection (thesis §5.1's three phases): types, derivatives, conversions, and the
// graphs that cannot be typed.
#include <gtest/gtest.h>

#include "compiler/conversions.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::compileText;
using memograph::testing::testLibrary;

std::optional<CheckReport> check(const std::string& text, Diagnostics& diagnostics) {
  return checkMaterial({"test.mgraph", text}, testLibrary(), diagnostics);
}

const LinkReport& linkNamed(const CheckReport& report, const std::string& name) {
  for (const auto& link : report.links) {
    if (link.name == name)
      return link;
  }
  throw std::runtime_error("no link " + name);
}

constexpr const char* kListing51 =
    "Mul A<0 B<1 Out>2;\nColorOutput In<3;\nAdd A<1 B<2 Out>3;\n"
    "Float1Constant 0.5 Out>1;\nNormalInput Out>0;\n";

TEST(TypeInference, Listing51GetsTheTypesOfListing53) {
  Diagnostics diagnostics;
  const auto report = check(kListing51, diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
  // Listing 5.3: the constant stays scalar and is converted; Mul and Add work on float3.
  EXPECT_EQ(linkNamed(*report, "link1").type, "float");
  EXPECT_EQ(linkNamed(*report, "link0").type, "float3");
  EXPECT_EQ(linkNamed(*report, "link2").type, "float3");
  EXPECT_EQ(linkNamed(*report, "link3").type, "float3");
  EXPECT_EQ(linkNamed(*report, "link1").consumers,
            (std::vector<std::string>{"Mul.B (as float3)", "Add.A (as float3)"}));
  EXPECT_FALSE(report->metadata.needsDerivatives);
}

TEST(TypeInference, DerivativesFlowOnlyUpstreamOfAConsumerThatNeedsThem) {
  Diagnostics diagnostics;
  const auto report = check(
      "UVInput UV>1;\n"
      "Mul A<1 B=4.0 Out>2;\n"  // scaled UVs feed the texture: need _D
      "ImageTexture \"a.png\" UV<2 Color>3;\n"
      "BaseColorOutput Color<3;\n"
      "Add A<1 B=0.5 Out>4;\n"  // the same UVs feed a plain computation
      "Wave In<4 Out>5;\n"
      "RoughnessOutput Roughness<5;\n",
      diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
  EXPECT_EQ(linkNamed(*report, "link1").type, "float2_D");
  EXPECT_EQ(linkNamed(*report, "link2").type, "float2_D");
  EXPECT_TRUE(linkNamed(*report, "link2").derivatives);
  EXPECT_EQ(linkNamed(*report, "link3").type, "float4");
  // The branch that needs no derivatives drops them right away and stays plain.
  EXPECT_EQ(linkNamed(*report, "link4").type, "float2");
  EXPECT_FALSE(linkNamed(*report, "link4").derivatives);
  EXPECT_TRUE(report->metadata.needsDerivatives);
}

TEST(TypeInference, WithoutADerivativeConsumerEverythingStaysPlain) {
  Diagnostics diagnostics;
  const auto report =
      check("UVInput UV>1;\nMul A<1 B=2 Out>2;\nBaseColorOutput Color<2;\n", diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
  for (const auto& link : report->links)
    EXPECT_FALSE(link.derivatives) << link.name;
}

TEST(TypeInference, ConstantsFeedingDerivativeInputsUseZeroDerivativeOverloads) {
  Diagnostics diagnostics;
  const auto report = check(
      "UVInput UV>1;\nFloat1Constant 3.0 Out>2;\nMul A<1 B<2 Out>3;\n"
      "ImageTexture \"t.png\" UV<3 Color>4;\nBaseColorOutput Color<4;\n",
      diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
  EXPECT_EQ(linkNamed(*report, "link2").type, "float_D");
  EXPECT_EQ(linkNamed(*report, "link3").type, "float2_D");
}

TEST(TypeInference, PrefersSplattingToTruncating) {
  Diagnostics diagnostics;
  // Squash takes float2 or float4: a float3 is extended (lossless), not truncated, even
  // though float2 is narrower.
  const auto report =
      check("NormalInput Out>1;\nSquash In<1 Out>2;\nRoughnessOutput Roughness<2;\n", diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
  EXPECT_NE(report->nodes[1].find("float4 In"), std::string::npos) << report->nodes[1];
}

TEST(TypeInference, IntConstantsConvertToFloat) {
  Diagnostics diagnostics;
  const auto report = check(
      "Pick Mode=1 A=(1, 0, 0) B<1 Out>2;\nNormalInput Out>1;\n"
      "BaseColorOutput Color<2;\n",
      diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
}

TEST(TypeInference, ReportsAGraphNeedingASecondDerivativeWithItsPath) {
  const auto run = compileText(
      "PositionInput Out>1;\nNormalFromPosition Position<1 Normal>2;\n"
      "ImageTexture \"t.png\" UV<2 Color>3;\nBaseColorOutput Color<3;\n");
  ASSERT_FALSE(run.material);
  const auto& d = run.diagnostics.all().front();
  EXPECT_NE(d.message.find("second derivative"), std::string::npos) << run.messages();
  EXPECT_EQ(d.location.line, 3u);
  ASSERT_FALSE(d.notes.empty());
  EXPECT_NE(d.notes[0].find("'ImageTexture' (test.mgraph:3:1) ← 'NormalFromPosition' "
                            "(test.mgraph:2:1) ← 'PositionInput' (test.mgraph:1:1)"),
            std::string::npos)
      << d.notes[0];
}

TEST(TypeInference, ReportsWhenNoOverloadFitsWithTheTypesThatArrived) {
  const auto run = compileText(
      "NormalInput Out>1;\nImageTexture \"t.png\" UV<1 Color>2;\nBaseColorOutput Color<2;\n");
  ASSERT_FALSE(run.material);
  const auto& d = run.diagnostics.all().front();
  EXPECT_NE(d.message.find("no overload of 'ImageTexture' fits what arrives at input 'UV'"),
            std::string::npos)
      << run.messages();
  EXPECT_EQ(d.location.line, 2u);
  EXPECT_NE(run.messages().find("can be: float3"), std::string::npos) << run.messages();
  EXPECT_NE(run.messages().find("could take: float2_D"), std::string::npos) << run.messages();
}

TEST(TypeInference, ReportsAmbiguityListingTheCandidates) {
  // Skew(float2, float4) and Skew(float4, float2) tie on every criterion for scalars.
  const auto run = compileText(
      "Float1Constant 1.0 Out>1;\nSkew A<1 B<1 Out>2;\n"
      "RoughnessOutput Roughness<2;\n");
  ASSERT_FALSE(run.material);
  const auto messages = run.messages();
  EXPECT_NE(messages.find("ambiguous: 2 overloads of 'Skew'"), std::string::npos) << messages;
  EXPECT_NE(messages.find("candidate: Skew(float2 A, float4 B) -> float Out"), std::string::npos);
  EXPECT_NE(messages.find("candidate: Skew(float4 A, float2 B) -> float Out"), std::string::npos);
  EXPECT_NE(messages.find("input 'A' arrives as float"), std::string::npos);
}

TEST(TypeInference, AmongEqualConversionsPrefersTheNarrowestTypes) {
  Diagnostics diagnostics;
  // float2 UVs into a float3 output: Mul on float2 then extend, not extend then Mul float3.
  const auto report =
      check("UVInput UV>1;\nMul A<1 B=2 Out>2;\nBaseColorOutput Color<2;\n", diagnostics);
  ASSERT_TRUE(report) << formatDiagnostics(diagnostics);
  EXPECT_EQ(linkNamed(*report, "link2").type, "float2");
  EXPECT_EQ(linkNamed(*report, "link2").consumers,
            std::vector<std::string>{"BaseColorOutput.Color (as float3)"});
}

TEST(TypeInference, ReportsConstantsNoOverloadAccepts) {
  const auto run =
      compileText("Pick Mode=1 A=\"x.png\" B=(1,2,3) Out>1;\nBaseColorOutput Color<1;\n");
  ASSERT_FALSE(run.material);
  EXPECT_NE(run.messages().find("takes a number"), std::string::npos) << run.messages();
}

TEST(Conversions, CostsAndExpressions) {
  const Type f{BaseType::Float, false}, f3{BaseType::Float3, false}, f3d{BaseType::Float3, true},
      f2d{BaseType::Float2, true}, i{BaseType::Int, false};
  EXPECT_EQ(*conversionCost(f3, f3), Cost{});
  EXPECT_EQ(*conversionCost(f, f3), (Cost{.conversions = 1}));
  EXPECT_EQ(*conversionCost(f3, f), (Cost{.conversions = 1, .truncations = 1}));
  EXPECT_EQ(*conversionCost(f3d, f3), (Cost{.droppedDerivatives = 1}));
  // int → float is exact and ranks below derivative work; to a vector it is also a splat.
  EXPECT_EQ(*conversionCost(i, f), (Cost{.intToFloat = 1}));
  EXPECT_EQ(*conversionCost(i, f3), (Cost{.conversions = 1}));
  EXPECT_LT(*conversionCost(i, f), (Cost{.derivativeWork = 1, .droppedDerivatives = 1}));
  EXPECT_FALSE(conversionCost(f3, f3d)) << "derivatives cannot be invented";
  EXPECT_FALSE(conversionCost(i, f3d));
  EXPECT_EQ(convertExpression("link0", f, f3), "mg_to_float3(link0)");
  EXPECT_EQ(convertExpression("link4", f3d, f), "mg_to_float(mg_drop_D(link4))");
  EXPECT_EQ(convertExpression("link4", f3d, f2d), "mg_to_float2_D(link4)");
  EXPECT_EQ(convertExpression("link4", f3, f3), "link4");
}

}  // namespace
}  // namespace memograph::compiler
