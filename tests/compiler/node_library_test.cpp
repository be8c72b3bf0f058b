// The node-library loader: signatures → overloads, @types templates, annotations, and the
// errors a library author gets.
#include <gtest/gtest.h>

#include "compiler/library_scanner.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::loadLibrary;
using memograph::testing::testLibrary;

const std::vector<SourceFile> kMinimalPrelude = {
    {"prelude/glsl.inc", "#define float3 vec3\n"},
    {"prelude/hlsl.inc", ""},
    {"prelude/common.inc",
     "struct MaterialInputs { float3 normal; };\n"
     "struct MaterialOutputs { float3 baseColor; };\n"}};

std::vector<SourceFile> withFamily(const std::string& text) {
  auto files = kMinimalPrelude;
  files.push_back({"family.inc", text});
  return files;
}

TEST(NodeLibrary, ParsesListing52CrossOverloadsFromTheirSignatures) {
  auto run = loadLibrary(
      withFamily("void Cross(in float3 A, in float3 B, out float3 Out) {\n  Out = cross(A, B);\n}\n"
                 "void Cross(in float3_D A, in float3_D B, out float3_D Out) {\n"
                 "  Out.v = cross(A.v, B.v);\n}\n"));
  ASSERT_FALSE(run.diagnostics.hasErrors()) << formatDiagnostics(run.diagnostics);
  const NodeType* cross = run.library.find("Cross");
  ASSERT_NE(cross, nullptr);
  ASSERT_EQ(cross->sockets.size(), 3u);
  EXPECT_EQ(cross->sockets[0].name, "A");
  EXPECT_EQ(cross->sockets[2].direction, Direction::Out);
  ASSERT_EQ(cross->overloads.size(), 2u);
  EXPECT_EQ(cross->overloads[1].socketTypes[0], (Type{BaseType::Float3, true}));
  EXPECT_EQ(cross->overloads[1].derivativeInputs, 2);
  EXPECT_EQ(cross->overloads[1].derivativeOutputs, 1);
  EXPECT_EQ(cross->file, "family.inc");
  EXPECT_EQ(cross->location.line, 1u);
}

TEST(NodeLibrary, InstantiatesTemplatesIncludingUnderscoreSegments) {
  auto run = loadLibrary(
      withFamily("/// Adds.\n"
                 "/// @types T = float, float3; S = float_D, float3_D\n"
                 "void Add(in T A, in S B, out T_D Out) { Out = mg_make_T_D(A, B.x, B.y); }\n"));
  ASSERT_FALSE(run.diagnostics.hasErrors()) << formatDiagnostics(run.diagnostics);
  const NodeType* add = run.library.find("Add");
  ASSERT_NE(add, nullptr);
  ASSERT_EQ(add->overloads.size(), 2u);
  EXPECT_EQ(add->overloads[1].socketTypes[0].name(), "float3");
  EXPECT_EQ(add->overloads[1].socketTypes[1].name(), "float3_D");
  EXPECT_EQ(add->overloads[1].socketTypes[2].name(), "float3_D");
  const auto& text = run.library.functions()[add->overloads[1].function].text;
  EXPECT_NE(text.find("mg_make_float3_D(A, B.x, B.y)"), std::string::npos) << text;
  EXPECT_EQ(add->description, "Adds.");
}

TEST(NodeLibrary, ReadsDefaultsInputsOutputsAndSinks) {
  auto run = loadLibrary(withFamily(
      "/// @output baseColor\n/// @default Color (0.8, 0.8, 0.8)\n"
      "void BaseColorOutput(in float3 Color, inout MaterialOutputs outputs) {}\n"
      "/// @input normal\n"
      "void NormalInput(in MaterialInputs inputs, out float3 Out) { Out = inputs.normal; }\n"));
  ASSERT_FALSE(run.diagnostics.hasErrors()) << formatDiagnostics(run.diagnostics);
  const NodeType* output = run.library.find("BaseColorOutput");
  ASSERT_NE(output, nullptr);
  EXPECT_TRUE(output->isSink);
  EXPECT_EQ(output->sockets.size(), 1u);  // `outputs` is context, not a socket
  EXPECT_EQ(output->outputsWritten, std::vector<std::string>{"baseColor"});
  EXPECT_EQ(output->defaults.at("Color").components.size(), 3u);
  const NodeType* normal = run.library.find("NormalInput");
  EXPECT_TRUE(normal->takesInputs);
  EXPECT_EQ(normal->inputsRead, std::vector<std::string>{"normal"});
}

TEST(NodeLibrary, LinksHelpersCalledFromNodesTransitively) {
  const NodeType* wave = testLibrary().find("Wave");
  ASSERT_NE(wave, nullptr);
  const auto& function = testLibrary().functions()[wave->overloads[0].function];
  ASSERT_EQ(function.callees.size(), 1u);
  const auto& helper = testLibrary().functions()[function.callees[0]];
  EXPECT_EQ(helper.name, "mg_wave");
  ASSERT_EQ(helper.callees.size(), 1u);
  EXPECT_EQ(testLibrary().functions()[helper.callees[0]].name, "mg_tri");
}

TEST(NodeLibrary, PreludeIsPerTargetWithTemplatesExpanded) {
  const auto& glsl = testLibrary().prelude(Target::Glsl);
  const auto& hlsl = testLibrary().prelude(Target::Hlsl);
  EXPECT_NE(glsl.find("#define float3 vec3"), std::string::npos);
  EXPECT_EQ(hlsl.find("#define float3 vec3"), std::string::npos);
  EXPECT_NE(hlsl.find("float3_D mg_const_float3_D(float3 v)"), std::string::npos);
  // The GLSL part comes before the portable part that relies on it.
  EXPECT_LT(glsl.find("#define float3"), glsl.find("struct float3_D"));
}

TEST(NodeLibrary, SuggestsCloseNamesForTypos) {
  const auto suggestions = testLibrary().suggestions("ImageTextur");
  ASSERT_FALSE(suggestions.empty());
  EXPECT_EQ(suggestions[0], "ImageTexture");
  EXPECT_TRUE(testLibrary().suggestions("Zzzzzzzzzzzzzz").empty());
}

struct LibraryErrorCase {
  const char* text;
  unsigned line;
  const char* message;
};

class NodeLibraryError : public ::testing::TestWithParam<LibraryErrorCase> {};

TEST_P(NodeLibraryError, NamesTheFileLineAndProblem) {
  const auto run = loadLibrary(withFamily(GetParam().text));
  ASSERT_TRUE(run.diagnostics.hasErrors());
  const auto& d = run.diagnostics.all().front();
  EXPECT_EQ(d.file, "family.inc");
  EXPECT_EQ(d.location.line, GetParam().line);
  EXPECT_NE(d.message.find(GetParam().message), std::string::npos) << d.message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, NodeLibraryError,
    ::testing::Values(
        LibraryErrorCase{"float kGlobal = 1.0;", 1, "expected a function definition"},
        LibraryErrorCase{"\nvoid A(in float3 X, out float3 Y) {", 2, "never closed"},
        LibraryErrorCase{"void A(in float3x3 X, out float3 Y) {}", 1, "of type 'float3x3'"},
        LibraryErrorCase{"void A(in float3 input, out float3 Y) {}", 1, "reserved"},
        LibraryErrorCase{
            "void A(in float3 X, out float3 Y) {}\nvoid A(in float3 Z, out float3 Y) {}", 2,
            "different sockets"},
        LibraryErrorCase{
            "void A(in float3 X, out float3 Y) {}\nvoid A(in float3 X, out float3 Y) {}", 2,
            "defined twice"},
        LibraryErrorCase{"/// @default Q 1.0\nvoid A(in float3 X, out float3 Y) {}", 2,
                         "not a socket"},
        LibraryErrorCase{"/// @types T = float; S = float, float2\nvoid A(in T X, out S Y) {}", 2,
                         "same number of types"},
        LibraryErrorCase{"/// @frobnicate\nvoid A(in float3 X, out float3 Y) {}", 2,
                         "unknown or malformed annotation"},
        LibraryErrorCase{"float helper(float x) { return x; }", 1, "neither a node"},
        LibraryErrorCase{"float4 mg_proto(float x);", 1, "prototypes"},
        LibraryErrorCase{"void A(in float3 X, inout float3 Y) {}", 1, "inout"}),
    [](const auto& info) { return "Case" + std::to_string(info.index); });

TEST(LibraryScanner, ReplaceWordLeavesLongerIdentifiersAlone) {
  EXPECT_EQ(replaceWord("T Tx xT T_D mg_T T2", "T", "float3"),
            "float3 Tx xT float3_D mg_float3 T2");
}

}  // namespace
}  // namespace memograph::compiler
