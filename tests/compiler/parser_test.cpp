// The .mgraph lexer and parser: thesis Listing 5.1 as-is, the extensions, syntax errors.
#include <gtest/gtest.h>

#include "compiler/lexer.h"
#include "compiler/parser.h"

namespace memograph::compiler {
namespace {

Graph parse(const std::string& text, Diagnostics& diagnostics,
            const std::string& path = "graphs/example.mgraph") {
  return parseGraph(SourceFile{path, text}, diagnostics);
}

TEST(Lexer, TokenizesSocketsLiteralsAndTracksLineAndColumn) {
  const auto tokens = tokenize("Mul A<0 B>12;\n  Scale=-2.5e1 \"wood.png\" (1, 2)");
  ASSERT_EQ(tokens.size(), 18u);
  EXPECT_EQ(tokens[0].kind, TokenKind::Identifier);
  EXPECT_EQ(tokens[2].kind, TokenKind::Less);
  EXPECT_EQ(tokens[3].text, "0");
  EXPECT_EQ(tokens[6].text, "12");
  EXPECT_EQ(tokens[8].location.line, 2u);
  EXPECT_EQ(tokens[8].location.column, 3u);
  EXPECT_EQ(tokens[10].text, "-2.5e1");
  EXPECT_EQ(tokens[11].kind, TokenKind::String);
  EXPECT_EQ(tokens[11].text, "wood.png");
  EXPECT_EQ(tokens.back().kind, TokenKind::End);
}

TEST(Lexer, CommentsRunToTheEndOfTheLine) {
  const auto tokens = tokenize("# a comment ; < >\nAdd; # another");
  ASSERT_EQ(tokens.size(), 3u);
  EXPECT_EQ(tokens[0].text, "Add");
  EXPECT_EQ(tokens[0].location.line, 2u);
}

TEST(Lexer, UnreadableBytesBecomeInvalidTokensWithAMessage) {
  const std::string source("Add \x01 @", 7);  // tokens view into it
  const auto tokens = tokenize(source);
  ASSERT_GE(tokens.size(), 3u);
  EXPECT_EQ(tokens[1].kind, TokenKind::Invalid);
  EXPECT_EQ(invalidTokenMessage(tokens[1]), "unexpected byte 0x01");
  EXPECT_EQ(invalidTokenMessage(tokens[2]), "unexpected character '@'");
}

TEST(Lexer, UnterminatedStringIsInvalid) {
  const auto tokens = tokenize("ImageTexture \"wood.png\nX");
  EXPECT_EQ(tokens[1].kind, TokenKind::Invalid);
  EXPECT_NE(invalidTokenMessage(tokens[1]).find("unterminated string"), std::string::npos);
}

TEST(Parser, ParsesThesisListing51AsIs) {
  Diagnostics diagnostics;
  const Graph graph = parse(
      "Mul A<0 B<1 Out>2;\n"
      "ColorOutput In<3;\n"
      "Add A<1 B<2 Out>3;\n"
      "Float1Constant 0.5 Out>1;\n"
      "NormalInput Out>0;\n",
      diagnostics);
  ASSERT_FALSE(diagnostics.hasErrors()) << formatDiagnostics(diagnostics);
  ASSERT_EQ(graph.nodes.size(), 5u);
  EXPECT_EQ(graph.name, "example");
  const Node& mul = graph.nodes[0];
  EXPECT_EQ(mul.type, "Mul");
  ASSERT_EQ(mul.inputs.size(), 2u);
  EXPECT_EQ(mul.inputs[0].socket, "A");
  EXPECT_EQ(mul.inputs[0].link, 0);
  EXPECT_EQ(mul.inputs[1].link, 1);
  ASSERT_EQ(mul.outputs.size(), 1u);
  EXPECT_EQ(mul.outputs[0].socket, "Out");
  EXPECT_EQ(mul.outputs[0].link, 2);
  const Node& constant = graph.nodes[3];
  ASSERT_EQ(constant.positional.size(), 1u);
  EXPECT_DOUBLE_EQ(constant.positional[0].components[0], 0.5);
  EXPECT_FALSE(constant.positional[0].isInteger);
  EXPECT_EQ(constant.location.line, 4u);
  EXPECT_EQ(constant.location.column, 1u);
}

TEST(Parser, ReadsConstantsTuplesStringsAndTheMaterialDeclaration) {
  Diagnostics diagnostics;
  const Graph graph = parse(
      "material Rusty_Metal;  # named explicitly\n"
      "Noise UV<1 Scale=5 Color=(0.8, 0.2, 0.1) Out>2;\n"
      "ImageTexture \"textures/wood.png\" UV<1 Color>3;\n",
      diagnostics);
  ASSERT_FALSE(diagnostics.hasErrors()) << formatDiagnostics(diagnostics);
  EXPECT_EQ(graph.name, "Rusty_Metal");
  ASSERT_EQ(graph.nodes.size(), 2u);
  const auto& constants = graph.nodes[0].constants;
  ASSERT_EQ(constants.size(), 2u);
  EXPECT_EQ(constants[0].socket, "Scale");
  EXPECT_TRUE(constants[0].value.isInteger);
  EXPECT_EQ(constants[1].value.kind, Literal::Kind::Tuple);
  EXPECT_EQ(constants[1].value.components, (std::vector<double>{0.8, 0.2, 0.1}));
  ASSERT_EQ(graph.nodes[1].positional.size(), 1u);
  EXPECT_EQ(graph.nodes[1].positional[0].kind, Literal::Kind::String);
  EXPECT_EQ(graph.nodes[1].positional[0].text, "textures/wood.png");
}

TEST(Parser, MaterialNameComesFromTheFileStem) {
  EXPECT_EQ(materialNameFromPath("a/b/rusty-metal.mgraph"), "rusty_metal");
  EXPECT_EQ(materialNameFromPath("3d.mgraph"), "M3d");
  EXPECT_EQ(materialNameFromPath(""), "M");
}

struct SyntaxCase {
  const char* text;
  unsigned line, column;
  const char* message;
};

class ParserSyntaxError : public ::testing::TestWithParam<SyntaxCase> {};

TEST_P(ParserSyntaxError, ReportsFileLineColumnAndWhatWasExpected) {
  const auto& c = GetParam();
  Diagnostics diagnostics;
  parse(c.text, diagnostics, "bad.mgraph");
  ASSERT_TRUE(diagnostics.hasErrors());
  const Diagnostic& d = diagnostics.all().front();
  EXPECT_EQ(d.file, "bad.mgraph");
  EXPECT_EQ(d.location.line, c.line);
  EXPECT_EQ(d.location.column, c.column);
  EXPECT_NE(d.message.find(c.message), std::string::npos) << d.message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ParserSyntaxError,
    ::testing::Values(SyntaxCase{"Mul A<0 B<1 Out>2", 1, 18, "missing ';'"},
                      SyntaxCase{"Mul A<x;", 1, 7, "expected a link id"},
                      SyntaxCase{"Mul A<-1;", 1, 7, "not a whole number"},
                      SyntaxCase{"Mul A;", 1, 5, "socket 'A' is not bound"},
                      SyntaxCase{"Mul A? 1;", 1, 6, "unexpected character '?'"},
                      SyntaxCase{"\n  < 1;", 2, 3, "expected a node type"},
                      SyntaxCase{"Mix C=(1, 2;", 1, 12, "expected ',' or ')'"},
                      SyntaxCase{"Mix C=(1, 2, 3, 4, 5);", 1, 7, "2 to 4 components"},
                      SyntaxCase{"Mix C=1e999;", 1, 7, "not a valid finite number"},
                      SyntaxCase{"Mix C=12abc;", 1, 7, "not a valid finite number"},
                      SyntaxCase{"material X Y;", 1, 12, "expected ';' after the material"}),
    [](const auto& info) { return "Case" + std::to_string(info.index); });

TEST(Parser, RecoversAtSemicolonsAndReportsEveryBrokenStatement) {
  Diagnostics diagnostics;
  const Graph graph = parse("Mul A<;\nAdd A<1 Out>2;\nSub B<;\n", diagnostics);
  EXPECT_EQ(diagnostics.errorCount(), 2u);
  ASSERT_EQ(graph.nodes.size(), 1u);
  EXPECT_EQ(graph.nodes[0].type, "Add");
}

TEST(Parser, StopsAfterTooManyErrors) {
  Diagnostics diagnostics;
  std::string junk;
  for (int i = 0; i < 1000; ++i)
    junk += "< ;";
  parse(junk, diagnostics);
  EXPECT_LE(diagnostics.errorCount(), 21u);
}

TEST(Parser, TableLiteralsHoldExactly1024Numbers) {
  std::string numbers;
  for (int i = 0; i < 1024; ++i)
    numbers += (i % 7 == 0 ? ", " : " ") + std::to_string(i);
  Diagnostics ok;
  const auto graph = parse("RampLookup Ramp=[" + numbers + "] Color>1;", ok);
  ASSERT_EQ(ok.errorCount(), 0u);
  ASSERT_EQ(graph.nodes.size(), 1u);
  const auto& table = graph.nodes[0].constants.at(0).value;
  EXPECT_EQ(table.kind, Literal::Kind::Table);
  ASSERT_EQ(table.components.size(), 1024u);
  EXPECT_EQ(table.components[1023], 1023.0);

  Diagnostics shortTable;
  parse("RampLookup Ramp=[1 2 3] Color>1;", shortTable);
  ASSERT_EQ(shortTable.errorCount(), 1u);
  EXPECT_NE(formatDiagnostics(shortTable)
                .find("1:17: error: a table has 1024 numbers (256 RGBA entries); "
                      "this one has 3"),
            std::string::npos)
      << formatDiagnostics(shortTable);

  Diagnostics longTable;
  parse("RampLookup Ramp=[" + numbers + " 5] Color>1;", longTable);
  EXPECT_NE(formatDiagnostics(longTable).find("this one has more"), std::string::npos)
      << formatDiagnostics(longTable);

  Diagnostics unclosed;
  parse("RampLookup Ramp=[1 2 ; Color>1;", unclosed);
  EXPECT_NE(formatDiagnostics(unclosed).find("expected a number or ']' in the table, found ';'"),
            std::string::npos)
      << formatDiagnostics(unclosed);
}

}  // namespace
}  // namespace memograph::compiler
