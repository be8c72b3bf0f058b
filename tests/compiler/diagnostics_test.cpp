// Every bad graph the issue names gets `file:line:col: error:` with the line, a caret and
// a helpful note; plus pruning, ordering and formatting.
#include <gtest/gtest.h>

#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::compileText;

struct BadGraph {
  const char* name;
  const char* text;
  unsigned line, column;
  const char* message;
  const char* note;  // expected in the notes, or ""
};

class BadGraphDiagnostic : public ::testing::TestWithParam<BadGraph> {};

TEST_P(BadGraphDiagnostic, PointsAtTheProblem) {
  const auto& c = GetParam();
  const auto run = compileText(c.text);
  ASSERT_FALSE(run.material.has_value());
  ASSERT_TRUE(run.diagnostics.hasErrors());
  const Diagnostic& d = run.diagnostics.all().front();
  EXPECT_EQ(d.severity, Severity::Error);
  EXPECT_EQ(d.file, "test.mgraph");
  EXPECT_EQ(d.location.line, c.line) << run.messages();
  EXPECT_EQ(d.location.column, c.column) << run.messages();
  EXPECT_NE(d.message.find(c.message), std::string::npos) << run.messages();
  if (*c.note)
    EXPECT_NE(run.messages().find(c.note), std::string::npos) << run.messages();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadGraphDiagnostic,
    ::testing::Values(
        BadGraph{"SyntaxError", "NormalInput Out>1\nColorOutput In<1;", 2, 1,
                 "socket 'ColorOutput' is not bound",
                 "is a ';' missing at the end of the line above?"},
        BadGraph{"UnknownNode", "NormalInput Out>1;\nColourOutput In<1;", 2, 1,
                 "unknown node type 'ColourOutput'", "did you mean 'ColorOutput'"},
        BadGraph{"UnknownSocket", "NormalInput Out>1;\nColorOutput Color<1;", 2, 13,
                 "'ColorOutput' has no input socket 'Color'", "its inputs: In"},
        BadGraph{"WrongDirection", "NormalInput Out<1;\nColorOutput In<1;", 1, 13,
                 "'Out' is an output of 'NormalInput'", ""},
        BadGraph{"LinkNeverProduced", "ColorOutput In<7;", 1, 13,
                 "link 7 is used here but no node produces it", "Out>7"},
        BadGraph{"LinkProducedTwice", "NormalInput Out>1;\nNormalInput Out>1;\nColorOutput In<1;",
                 2, 13, "link 1 is produced twice",
                 "first produced by 'NormalInput' at test.mgraph:1:1"},
        BadGraph{"Cycle", "Add A<2 B=1 Out>1;\nMul A<1 B=2 Out>2;\nColorOutput In<2;", 1, 5,
                 "closes a cycle",
                 "cycle: 'Add' at test.mgraph:1:1 → 'Mul' at test.mgraph:2:1 → 'Add'"},
        BadGraph{"NoOverloadFits",
                 "NormalInput Out>1;\nImageTexture \"t.png\" UV<1 Color>2;\n"
                 "BaseColorOutput Color<2;",
                 2, 22, "no overload of 'ImageTexture'", "can be: float3"},
        BadGraph{"Ambiguous",
                 "Float1Constant 1.0 Out>1;\nSkew A<1 B<1 Out>2;\nRoughnessOutput Roughness<2;", 2,
                 1, "ambiguous", "candidate: Skew(float2 A, float4 B)"},
        BadGraph{"SecondDerivative",
                 "PositionInput Out>1;\nNormalFromPosition Position<1 Normal>2;\n"
                 "ImageTexture \"t.png\" UV<2 Color>3;\nBaseColorOutput Color<3;",
                 3, 22, "second derivative", "path:"},
        BadGraph{"NoOutput", "NormalInput Out>1;\nMul A<1 B=2 Out>2;", 1, 1, "has no output node",
                 "BaseColorOutput"},
        BadGraph{"UnconnectedInputWithoutDefault", "ColorOutput;", 1, 1,
                 "input 'In' of 'ColorOutput' is not connected and has no default", "In=…"},
        BadGraph{"TooManyValues", "Float1Constant 1.0 2.0 Out>1;\nRoughnessOutput Roughness<1;", 1,
                 20, "too many values", ""},
        BadGraph{"StringForANumber", "Mul A=\"x\" Out>1;\nColorOutput In<1;", 1, 7,
                 "takes a number", ""},
        BadGraph{"NumberForATexture",
                 "UVInput UV>1;\nImageTexture 3 UV<1 Color>2;\n"
                 "BaseColorOutput Color<2;",
                 2, 14, "texture path in quotes", ""},
        BadGraph{"FractionForAnInt", "Pick Mode=0.5 A=1 B=2 Out>1;\nColorOutput In<1;", 1, 11,
                 "whole number", ""},
        BadGraph{"InputBoundTwice", "Mul A=1 A=2 Out>1;\nColorOutput In<1;", 1, 9, "bound twice",
                 ""},
        BadGraph{"ReservedMaterialName", "material my__mat;\nNormalInput Out>1;\nColorOutput In<1;",
                 1, 10, "reserved in GLSL", ""}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Diagnostics, FormatShowsTheLineAndACaretUnderTheColumn) {
  const auto run = compileText("NormalInput Out>1;\nColorOutput\tColor<1;\n",
                               testing::testLibrary(), "g/m.mgraph");
  ASSERT_FALSE(run.material);
  const std::string text = formatDiagnostic(run.diagnostics.all().front());
  EXPECT_EQ(text,
            "g/m.mgraph:2:13: error: 'ColorOutput' has no input socket 'Color'\n"
            "    ColorOutput\tColor<1;\n"
            "               \t^\n"
            "    its inputs: In\n"
            "    its outputs: none\n");
}

TEST(Diagnostics, ABrokenProducerDoesNotCascadeIntoItsConsumers) {
  const auto unknownNode = compileText("Foo Out>1;\nMul A<1 B=2 Out>2;\nColorOutput In<2;\n");
  EXPECT_EQ(unknownNode.diagnostics.errorCount(), 1u) << unknownNode.messages();
  const auto unknownSocket = compileText("NormalInput Normal>1;\nColorOutput In<1;\n");
  EXPECT_EQ(unknownSocket.diagnostics.errorCount(), 1u) << unknownSocket.messages();
}

TEST(Diagnostics, NodesThatReachNoOutputAreDroppedWithAWarning) {
  const auto run = compileText("NormalInput Out>1;\nColorOutput In<1;\nMul A=1 B=2 Out>9;\n");
  ASSERT_TRUE(run.material) << run.messages();
  ASSERT_EQ(run.diagnostics.all().size(), 1u);
  const auto& d = run.diagnostics.all().front();
  EXPECT_EQ(d.severity, Severity::Warning);
  EXPECT_EQ(d.location.line, 3u);
  EXPECT_NE(d.message.find("does not reach any output"), std::string::npos);
  EXPECT_EQ(run.material->glsl.find("Mul("), std::string::npos);
  EXPECT_EQ(run.material->metadata.nodeCount, 2u);
}

TEST(Diagnostics, ADeepChainNeitherOverflowsTheStackNorFails) {
  std::string text = "Float1Constant 1.0 Out>0;\n";
  for (int i = 1; i <= 20000; ++i) {
    text += "Add A<" + std::to_string(i - 1) + " B=1 Out>" + std::to_string(i) + ";\n";
  }
  text += "RoughnessOutput Roughness<20000;\n";
  const auto run = compileText(text);
  EXPECT_TRUE(run.material) << run.messages();
}

}  // namespace
}  // namespace memograph::compiler
