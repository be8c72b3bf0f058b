// Derivatives that would be dropped or invented, the int → float cost, and
// phase 3's exhaustive fallback on graphs that are not trees (docs/guide/graph-format.md).
#include <gtest/gtest.h>

#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::loadLibrary;
using memograph::testing::realLibrary;

struct Checked {
  std::optional<CheckReport> report;
  Diagnostics diagnostics;
  std::string messages() const { return formatDiagnostics(diagnostics); }
  std::size_t warnings() const {
    std::size_t count = 0;
    for (const auto& d : diagnostics.all())
      count += d.severity == Severity::Warning;
    return count;
  }
};

Checked check(const std::string& text, const NodeLibrary& library = realLibrary()) {
  Checked run;
  run.report = checkMaterial({"test.mgraph", text}, library, run.diagnostics);
  return run;
}

const LinkReport& linkNamed(const CheckReport& report, const std::string& name) {
  for (const auto& link : report.links) {
    if (link.name == name)
      return link;
  }
  throw std::runtime_error("no link " + name);
}

// --- Derivatives that reach plain sockets ------------------------------------------------

TEST(DerivativeRules, WarnsWhenAVaryingValueEntersAPlainSocketWhoseNodeDerivativesAreNeeded) {
  const auto run = check(
      "UVInput Out>1;\n"
      "Separate2 Vector<1 X>2 Y>3;\n"
      "Mapping Vector<1 Scale<2 Out>4;\n"  // Scale varies; Mapping has no _D Scale
      "ImageTexture \"a.png\" UV<4 Color>5;\n"
      "BaseColorOutput In<5;\n");
  ASSERT_TRUE(run.report) << run.messages();
  ASSERT_EQ(run.warnings(), 1u) << run.messages();
  const std::string text = run.messages();
  EXPECT_NE(text.find("test.mgraph:3:"), std::string::npos) << text;
  EXPECT_NE(text.find("'Mapping'"), std::string::npos) << text;
  EXPECT_NE(text.find("'Scale'"), std::string::npos) << text;
  EXPECT_NE(text.find("'ImageTexture' (test.mgraph:4:1)"), std::string::npos) << text;
  EXPECT_NE(text.find("'Separate2' (test.mgraph:2:1)"), std::string::npos) << text;
}

TEST(DerivativeRules, NoWarningForConstantsOrWhenNoConsumerNeedsTheDerivatives) {
  // A constant Scale: nothing varies.
  auto run = check(
      "UVInput Out>1;\n"
      "Mapping Vector<1 Scale=(2, 2, 2) Out>4;\n"
      "ImageTexture \"a.png\" UV<4 Color>5;\n"
      "BaseColorOutput In<5;\n");
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(run.warnings(), 0u) << run.messages();
  // A varying Scale, but Mapping's output feeds no consumer of derivatives.
  run = check(
      "UVInput Out>1;\n"
      "Separate2 Vector<1 X>2 Y>3;\n"
      "Mapping Vector<1 Scale<2 Out>4;\n"
      "BaseColorOutput In<4;\n");
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(run.warnings(), 0u) << run.messages();
  EXPECT_FALSE(linkNamed(*run.report, "link4").derivatives);
  // A value that does not vary over the footprint (time) into the plain socket.
  run = check(
      "UVInput Out>1;\n"
      "TimeInput Out>2;\n"
      "Mapping Vector<1 Scale<2 Out>4;\n"
      "ImageTexture \"a.png\" UV<4 Color>5;\n"
      "BaseColorOutput In<5;\n");
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(run.warnings(), 0u) << run.messages();
}

// A library where one socket has a _D overload only together with plain other sockets:
// the cost order must keep the derivatives of a varying input rather than drop them.
const NodeLibrary& mixedLibrary() {
  static const auto run = loadLibrary({
      {"prelude/glsl.inc", ""},
      {"prelude/hlsl.inc", ""},
      {"prelude/common.inc",
       "struct float_D { float v; float x; float y; };\n"
       "struct MaterialInputs { float_D u; float3 normal; };\n"
       "struct MaterialOutputs { float roughness; };\n"},
      {"family.inc",
       "/// @input uv\n"
       "void U(in MaterialInputs inputs, out float_D Out) { Out = inputs.u; }\n"
       "void Blend(in float_D A, in float F, out float_D Out) { Out = A; }\n"
       "void Blend(in float_D A, in float_D F, out float_D Out) { Out = A; }\n"
       "void Blend(in float A, in float F, out float Out) { Out = A; }\n"
       "void Sample(in float_D X, out float Out) { Out = X.v; }\n"
       "/// @output roughness\n"
       "void Sink(in float In, inout MaterialOutputs outputs) { outputs.roughness = In; }\n"},
  });
  EXPECT_FALSE(run.diagnostics.hasErrors()) << formatDiagnostics(run.diagnostics);
  return run.library;
}

TEST(DerivativeRules, ASocketWithADerivativeOverloadKeepsTheDerivativesOfAVaryingValue) {
  const auto run =
      check("U Out>1;\nBlend A<1 F<1 Out>2;\nSample X<2 Out>3;\nSink In<3;\n", mixedLibrary());
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(run.warnings(), 0u) << run.messages();
  EXPECT_EQ(run.report->nodes[1], "Blend(float_D A, float_D F) -> float_D Out");
}

// --- Derivatives that would be invented ----------------------------------------------------

TEST(DerivativeRules, InputsWithoutDerivativesAreRejectedWhereDerivativesAreNeeded) {
  for (const std::string node : {"NormalInput", "TangentInput", "VertexColorInput"}) {
    const auto run = check(node + " Out>1;\nMul A<1 B=2 Out>2;\n" +
                           "ImageTexture \"a.png\" UV<2 Color>3;\nBaseColorOutput In<3;\n");
    EXPECT_FALSE(run.report) << node;
    const std::string text = run.messages();
    EXPECT_NE(text.find("never invents"), std::string::npos) << text;
    EXPECT_NE(text.find("but they would come from '" + node + "' (test.mgraph:1:1)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("path: 'Mul' (test.mgraph:2:1) ← '" + node + "' (test.mgraph:1:1)"),
              std::string::npos)
        << text;
  }
}

TEST(DerivativeRules, InputsWithoutDerivativesStillFeedPlainSockets) {
  const auto run = check(
      "NormalInput Out>1;\nMul A<1 B=0.5 Out>2;\nBaseColorOutput In<2;\n"
      "VertexColorInput Out>3 Alpha>4;\nRoughnessOutput In<4;\n");
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(linkNamed(*run.report, "link1").type, "float3");
  EXPECT_EQ(linkNamed(*run.report, "link4").type, "float");
}

TEST(DerivativeRules, OnlyFootprintVaryingSourcesWithoutDerivativesAreMarked) {
  auto invents = [](const char* name) {
    const NodeType* type = realLibrary().find(name);
    EXPECT_NE(type, nullptr) << name;
    bool any = false;
    for (const auto& overload : type->overloads)
      any = any || overload.inventsDerivatives;
    return any;
  };
  EXPECT_TRUE(invents("NormalInput"));
  EXPECT_TRUE(invents("TangentInput"));
  EXPECT_TRUE(invents("VertexColorInput"));
  EXPECT_TRUE(invents("ViewInput"));
  EXPECT_FALSE(invents("UVInput"));
  EXPECT_FALSE(invents("PositionInput"));
  EXPECT_FALSE(invents("TimeInput"));  // constant over a footprint: zero is right
  EXPECT_FALSE(invents("Float3Constant"));
}

// --- int → float ---------------------------------------------------------------------------

TEST(DerivativeRules, AnIntConstantIntoAFloatSocketUsesThePlainOverload) {
  const auto run = check("IntConstant 3 Out>1;\nAdd A<1 B=0.5 Out>2;\nRoughnessOutput In<2;\n");
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(linkNamed(*run.report, "link1").type, "int");
  EXPECT_FALSE(run.report->metadata.needsDerivatives);
  EXPECT_EQ(linkNamed(*run.report, "link1").consumers,
            (std::vector<std::string>{"Add.A (as float)"}));
}

TEST(DerivativeRules, AnIntConstantStillFeedsADerivativeSocket) {
  const auto run = check(
      "UVInput Out>1;\nIntConstant 3 Out>2;\nMul A<1 B<2 Out>3;\n"
      "ImageTexture \"a.png\" UV<3 Color>4;\nBaseColorOutput In<4;\n");
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(linkNamed(*run.report, "link2").type, "float_D");
}

// --- Phase 3 on a DAG -------------------------------------------------------------------------

// P feeds both sinks. Alone, SinkA prefers P's int overload and SinkB P's float_D one (its
// int overload needs a conversion for Y), so the greedy pass finds no overload of P that
// fits both; the exhaustive search takes P = float_D, SinkA = float_D.
constexpr const char* kDagFamily =
    "void P(out int Out) { Out = 1; }\n"
    "void P(out float_D Out) { Out.v = 1.0; Out.x = 0.0; Out.y = 0.0; }\n"
    "/// @input uv\n"
    "void U(in MaterialInputs inputs, out float_D Out) { Out = inputs.u; }\n"
    "/// @output roughness\n"
    "void SinkA(in int X, inout MaterialOutputs outputs) { outputs.roughness = 1.0; }\n"
    "/// @output roughness\n"
    "void SinkA(in float_D X, inout MaterialOutputs outputs) { outputs.roughness = X.v; }\n"
    "/// @output metallic\n"
    "void SinkB(in float_D X, in float_D Y, inout MaterialOutputs outputs) {\n"
    "  outputs.metallic = X.v;\n}\n"
    "/// @output metallic\n"
    "void SinkB(in int X, in float2 Y, inout MaterialOutputs outputs) {\n"
    "  outputs.metallic = Y.x;\n}\n"
    // For the bound: free two-way choices multiply the combinations.
    "void F(out int Out) { Out = 1; }\n"
    "void F(out float_D Out) { Out.v = 1.0; Out.x = 0.0; Out.y = 0.0; }\n"
    "void Drain(in float X, inout MaterialOutputs outputs) { outputs.opacity = X; }\n"
    "void Flip(in int X, out float_D Out) { Out.v = 1.0; Out.x = 0.0; Out.y = 0.0; }\n"
    "void Flip(in float_D X, out int Out) { Out = 1; }\n"
    "/// @output opacity\n"
    "void Same(in int X, in int Y, inout MaterialOutputs outputs) { outputs.opacity = 1.0; }\n"
    "/// @output opacity\n"
    "void Same(in float_D X, in float_D Y, inout MaterialOutputs outputs) {\n"
    "  outputs.opacity = 0.0;\n}\n";

const NodeLibrary& dagLibrary() {
  static const auto run = loadLibrary({
      {"prelude/glsl.inc", ""},
      {"prelude/hlsl.inc", ""},
      {"prelude/common.inc",
       "struct float_D { float v; float x; float y; };\n"
       "struct MaterialInputs { float_D u; };\n"
       "struct MaterialOutputs { float roughness; float metallic; float opacity; };\n"},
      {"family.inc", kDagFamily},
  });
  EXPECT_FALSE(run.diagnostics.hasErrors()) << formatDiagnostics(run.diagnostics);
  return run.library;
}

TEST(TypeInferenceSearch, FindsTheAssignmentTheGreedyPassMissesOnASharedNode) {
  const auto run = check("P Out>1;\nU Out>2;\nSinkA X<1;\nSinkB X<1 Y<2;\n", dagLibrary());
  ASSERT_TRUE(run.report) << run.messages();
  EXPECT_EQ(linkNamed(*run.report, "link1").type, "float_D");
  EXPECT_EQ(linkNamed(*run.report, "link1").consumers,
            (std::vector<std::string>{"SinkA.X", "SinkB.X"}));
}

TEST(TypeInferenceSearch, ReportsNoFitWhenNoCombinationExists) {
  // P → Flip → Same.Y and P → Same.X: Same needs equal types, Flip makes them differ.
  // Every edge alone has a partner (phases 1 and 2 pass); no whole assignment exists.
  const auto run = check("P Out>1;\nFlip X<1 Out>2;\nSame X<1 Y<2;\n", dagLibrary());
  EXPECT_FALSE(run.report);
  const std::string text = run.messages();
  EXPECT_NE(text.find("fits all the nodes its outputs feed"), std::string::npos) << text;
  EXPECT_EQ(text.find("gave up"), std::string::npos) << text;
}

TEST(TypeInferenceSearch, GivesUpWithAClearErrorPastTheBound) {
  // 24 free two-way choices (each F fits its Drain either way), scheduled before the same
  // impossible triangle: 2^24 combinations, none valid.
  std::string graph;
  for (int i = 0; i < 24; ++i)
    graph += "Drain X<" + std::to_string(100 + i) + ";\nF Out>" + std::to_string(100 + i) + ";\n";
  graph += "P Out>1;\nFlip X<1 Out>2;\nSame X<1 Y<2;\n";
  const auto run = check(graph, dagLibrary());
  EXPECT_FALSE(run.report);
  const std::string text = run.messages();
  EXPECT_NE(text.find("gave up its exhaustive search after 1000000 overload combinations"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace memograph::compiler
