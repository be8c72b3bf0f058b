// A smoke fuzzer that runs in every test run (the libFuzzer target needs clang; see
// docs/design/testing.md): deterministic random bytes, token soup and mutated valid graphs go
// through compileMaterial with the test library. Each input must come back, and a failed
// compile must carry an error that points into the file. Also replays the inputs that once
// broke the compiler (tests/compiler/testdata/regressions/).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/compiler.h"
#include "deterministic_random.h"
#include "graph_generator.h"

namespace memograph::compiler {
namespace {

// The inputs are the same on every standard library.
using Random = testing::DeterministicRandom;

// Whether `d` points at a line of `file` and a column on it (or just past its end, where
// "missing ';'" and "unexpected end of file" point).
bool pointsInto(const Diagnostic& d, const SourceFile& file) {
  const auto lines =
      static_cast<std::uint32_t>(std::count(file.text.begin(), file.text.end(), '\n') + 1);
  if (d.location.line < 1 || d.location.line > lines || d.location.column < 1)
    return false;
  return d.location.column <= file.lineText(d.location.line).size() + 1;
}

// Compiles `text`; returns a failure message, or an empty string when the compiler behaved.
std::string compileAndCheck(const std::string& name, std::string text) {
  const SourceFile file{name, std::move(text)};
  Diagnostics diagnostics;
  const auto compiled = compileMaterial(file, testing::testNodeLibrary(), {}, diagnostics);
  formatDiagnostics(diagnostics);  // the caret display must cope with any line, too
  if (compiled)
    return {};
  if (!diagnostics.hasErrors())
    return "the compile failed without an error";
  for (const auto& d : diagnostics.all()) {
    if (d.severity == Severity::Error && pointsInto(d, file))
      return {};
  }
  return "no error points into the file:\n" + formatDiagnostics(diagnostics);
}

// Runs `make(random)` `count` times and reports every input the compiler mishandled.
template <typename Make>
void fuzz(std::uint64_t seed, int count, Make make) {
  Random random(seed);
  int failures = 0;
  for (int i = 0; i < count && failures < 5; ++i) {
    std::string input = make(random);
    const std::string problem = compileAndCheck("random_" + std::to_string(i) + ".mgraph", input);
    if (!problem.empty()) {
      ++failures;
      ADD_FAILURE() << "input " << i << " of seed " << seed << ": " << problem << "\ninput:\n"
                    << input;
    }
  }
}

TEST(RandomInput, RandomBytesComeBackWithAPositionedErrorOrAResult) {
  fuzz(1, 1500, [](Random& random) {
    std::string text(random.below(300), '\0');
    for (auto& c : text)
      c = static_cast<char>(random.next());
    return text;
  });
}

// Bytes drawn from the grammar's alphabet hit the lexer's and parser's corners more often.
TEST(RandomInput, GraphAlphabetSoupComesBackWithAPositionedErrorOrAResult) {
  static constexpr std::string_view kAlphabet = "Mul A<0 B>1=;\n#()\",.-+e9Float1Constant";
  fuzz(2, 1500, [](Random& random) {
    std::string text(random.below(200), ' ');
    for (auto& c : text)
      c = kAlphabet[random.below(kAlphabet.size())];
    return text;
  });
}

TEST(RandomInput, TokenSoupComesBackWithAPositionedErrorOrAResult) {
  static const std::vector<std::string> kTokens = {"Float1Constant",
                                                   "Float3Constant",
                                                   "NormalInput",
                                                   "UVInput",
                                                   "PositionInput",
                                                   "TimeInput",
                                                   "Add",
                                                   "Mul",
                                                   "Wave",
                                                   "Pick",
                                                   "Squash",
                                                   "ImageTexture",
                                                   "NormalFromPosition",
                                                   "ColorOutput",
                                                   "BaseColorOutput",
                                                   "RoughnessOutput",
                                                   "EmissionOutput",
                                                   "Mull",
                                                   "material",
                                                   "gl_M",
                                                   "A",
                                                   "B",
                                                   "In",
                                                   "Out",
                                                   "UV",
                                                   "Color",
                                                   "Value",
                                                   "Mode",
                                                   "Image",
                                                   "Roughness",
                                                   "Normal",
                                                   "Position",
                                                   "inputs",
                                                   "outputs",
                                                   "<",
                                                   ">",
                                                   "=",
                                                   ";",
                                                   ";",
                                                   ";",
                                                   "(",
                                                   ")",
                                                   ",",
                                                   "0",
                                                   "1",
                                                   "2",
                                                   "3",
                                                   "7",
                                                   "-1",
                                                   "0.5",
                                                   "+2",
                                                   "1e999",
                                                   "-0",
                                                   "9223372036854775807",
                                                   "9223372036854775808",
                                                   "99999999999999999999",
                                                   "1e-400",
                                                   "4.",
                                                   ".5",
                                                   "-.",
                                                   "12abc",
                                                   "\"wood.png\"",
                                                   "\"\"",
                                                   "\"unterminated",
                                                   "# comment\n",
                                                   "\n",
                                                   "\t",
                                                   "(1, 2, 3)",
                                                   "(1,2,3,4,5)",
                                                   "(0.5)",
                                                   "\xff",
                                                   "\x01",
                                                   "@"};
  fuzz(3, 2000, [](Random& random) {
    std::string text;
    const std::size_t count = random.below(60);
    for (std::size_t i = 0; i < count; ++i) {
      text += kTokens[random.below(kTokens.size())];
      if (random.below(3) != 0)
        text += ' ';
    }
    return text;
  });
}

// Valid graphs with a few edits: the inputs closest to what users write by mistake.
TEST(RandomInput, MutatedGeneratedGraphsComeBackWithAPositionedErrorOrAResult) {
  std::vector<std::string> graphs;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    testing::GraphShape shape;
    shape.nodeCount = 5 + seed * 4;
    shape.seed = seed;
    shape.textures = seed % 3 != 0;
    graphs.push_back(testing::generateGraph(shape));
  }
  static constexpr std::string_view kInsertions[] = {";",
                                                     "<",
                                                     ">",
                                                     "=",
                                                     "Mul ",
                                                     " Out>1",
                                                     " A<0",
                                                     " B=(1, 2)",
                                                     "\"x.png\"",
                                                     "#",
                                                     "\n",
                                                     "material M;",
                                                     "-",
                                                     "9",
                                                     "Wave In<3 Out>3;",
                                                     " Roughness=0.5"};
  fuzz(4, 2000, [&](Random& random) {
    std::string text = graphs[random.below(graphs.size())];
    const std::size_t edits = 1 + random.below(4);
    for (std::size_t e = 0; e < edits; ++e) {
      const std::size_t at = random.below(text.size() + 1);
      switch (random.below(5)) {
        case 0:  // delete a run of bytes
          text.erase(at, random.below(12));
          break;
        case 1: {  // insert a piece of syntax
          const auto& piece = kInsertions[random.below(std::size(kInsertions))];
          text.insert(at, piece);
          break;
        }
        case 2:  // change a byte
          if (at < text.size())
            text[at] = static_cast<char>(random.next());
          break;
        case 3: {  // duplicate a line (a link produced twice, a second sink…)
          const std::size_t begin = text.rfind('\n', at == 0 ? 0 : at - 1);
          const std::size_t end = text.find('\n', at);
          const std::size_t from = begin == std::string::npos ? 0 : begin + 1;
          if (end != std::string::npos)
            text.insert(from, text.substr(from, end + 1 - from));
          break;
        }
        default:  // renumber a link (cycles, dangling inputs)
          for (std::size_t i = at; i < text.size(); ++i) {
            if (text[i] >= '0' && text[i] <= '9') {
              text[i] = static_cast<char>('0' + random.below(10));
              break;
            }
          }
      }
    }
    return text;
  });
}

TEST(RandomInput, LongChainsAndDeepNestingComeBack) {
  // Deep graphs stress the iterative passes (no recursion may overflow the stack).
  std::string chain = "Float1Constant 1 Out>0;\n";
  for (int i = 0; i < 20000; ++i)
    chain += "Add A<" + std::to_string(i) + " B=1 Out>" + std::to_string(i + 1) + ";\n";
  chain += "RoughnessOutput Roughness<20000;\n";
  EXPECT_EQ(compileAndCheck("chain.mgraph", chain), "");
  EXPECT_EQ(compileAndCheck("parens.mgraph", "Float3Constant " + std::string(50000, '(')), "");
  EXPECT_EQ(compileAndCheck("semicolons.mgraph", std::string(50000, ';')), "");
}

// Thousands of bad lines once cost a copy of the line and a scan from the top of the file
// for each diagnostic: quadratic time (26 s for 50,000 lines) and, for one long line,
// gigabytes of memory.
TEST(RegressionInputs, ThousandsOfProblemsKeepABoundedNumberOfDiagnostics) {
  std::string unknownNodes, unreachedNodes = "RoughnessOutput;\n";
  for (int i = 0; i < 20000; ++i) {
    unknownNodes += "Foo" + std::to_string(i) + ";\n";
    unreachedNodes += "NormalInput Out>" + std::to_string(i) + ";\n";
  }
  for (const auto& text : {unknownNodes, unreachedNodes}) {
    const SourceFile file{"many.mgraph", text};
    Diagnostics diagnostics;
    compileMaterial(file, testing::testNodeLibrary(), {}, diagnostics);
    EXPECT_LE(diagnostics.all().size(), Diagnostics::kMaxKeptPerFile + 1);
    EXPECT_EQ(diagnostics.all().back().message,
              "too many problems in this file; the rest are not shown");
  }
  Diagnostics diagnostics;
  compileMaterial({"many.mgraph", unknownNodes}, testing::testNodeLibrary(), {}, diagnostics);
  EXPECT_EQ(diagnostics.errorCount(), 20000u) << "errors past the limit must still count";
}

// did-you-mean computed the edit distance from every unknown name to every node name: a
// 2 MB name took 6.5 s (0.11 s now: names too long to be close are skipped).
TEST(RegressionInputs, AHugeUnknownNodeNameIsReportedQuickly) {
  const SourceFile file{"huge.mgraph", std::string(4'000'000, 'X') + ";\n"};
  Diagnostics diagnostics;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(compileMaterial(file, testing::testNodeLibrary(), {}, diagnostics));
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_LT(elapsed, std::chrono::seconds(3));
  EXPECT_EQ(diagnostics.errorCount(), 1u);
}

// Numbers a shader cannot hold compiled "successfully" into code no shader compiler takes:
// `inf.0` for 1e300, and an int socket's 1e20 through llround as -9223372036854775808.
TEST(RegressionInputs, NumbersOutsideShaderRangesAreErrors) {
  const auto errorFor = [](const std::string& text) {
    Diagnostics diagnostics;
    const auto compiled =
        compileMaterial({"range.mgraph", text}, testing::testNodeLibrary(), {}, diagnostics);
    return compiled ? std::string("(compiled)") : diagnostics.all().front().message;
  };
  EXPECT_EQ(errorFor("Float1Constant 1e300 Out>1; RoughnessOutput Roughness<1;"),
            "'1e300' is too large for a 32-bit float (at most 3.4028235e38)");
  EXPECT_EQ(
      errorFor("Float3Constant 1 0 0 Out>1; Pick 4294967296 A<1 B<1 Out>2; ColorOutput In<2;"),
      "input 'Mode' of 'Pick' takes a whole number from -2147483648 to 2147483647 (a shader "
      "int)");
  EXPECT_EQ(errorFor("Float1Constant 3.4e38 Out>1; RoughnessOutput Roughness<1;"), "(compiled)");
  EXPECT_EQ(
      errorFor("Float3Constant 1 0 0 Out>1; Pick -2147483648 A<1 B<1 Out>2; ColorOutput In<2;"),
      "(compiled)");
}

TEST(RegressionInputs, EachComesBackWithAPositionedErrorOrAResult) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(MEMOGRAPH_REGRESSIONS_DIR)) {
    if (entry.is_regular_file() && entry.path().extension() == ".mgraph")
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty()) << "no regression inputs in " << MEMOGRAPH_REGRESSIONS_DIR;
  for (const auto& path : files) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(compileAndCheck(path.filename().string(), text.str()), "") << path;
  }
}

}  // namespace
}  // namespace memograph::compiler
