// import-blender's check of a staged export (tools/cli/staged_import.h), index.json's part:
// the exporter's shape is accepted, and each other shape is refused with a message naming
// what is wrong and its byte in index.json.
#include "tools/cli/staged_import.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace memograph::cli {
namespace {

namespace fs = std::filesystem;

class StagedIndex : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("memograph-staged-index-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "a.mgraph") << "material a;\nBaseColorOutput (1.0, 0.0, 0.0);\n";
    std::ofstream(dir_ / "b.mgraph") << "material b;\nRoughnessOutput 0.5;\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The check's message for an export holding a.mgraph, b.mgraph and this index ("" when
  // accepted).
  std::string check(const std::string& index) {
    std::ofstream(dir_ / "index.json", std::ios::trunc) << index;
    StagedExportExpectation expected;
    expected.reportedMaterials = 2;
    return validateStagedExport(dir_, "DIR", expected);
  }

  fs::path dir_;
};

constexpr const char* kA = R"("A": {"file": "a.mgraph", "material": "a"})";

TEST_F(StagedIndex, TheExportersShapeIsAccepted) {
  EXPECT_EQ(check(R"({"materials": {"A": {"file": "a.mgraph", "material": "a"},
                     "B \u00e9": {"material": "b", "file": "b.mgraph"}}})"),
            "");
  // Escapes are resolved: json.dumps writes a name outside the BMP as a surrogate pair.
  EXPECT_EQ(check(R"( {"materials": {"\ud83d\ude00": {"file": "a.mgraph", "material": "a"},
                     "B": {"file": "b.mgraph", "material": "\u0062"}}} )"),
            "");
}

TEST_F(StagedIndex, InvalidJsonIsRefusedWithItsByte) {
  EXPECT_EQ(check("{["),
            "DIR/index.json: not the exporter's index: expected a member name, found '[' (at "
            "byte 1)");
  EXPECT_EQ(check(R"({"materials": [)"),
            "DIR/index.json: not the exporter's index: unexpected end of the JSON, expected a "
            "value (at byte 15)");
  EXPECT_EQ(check(std::string(R"({"materials": {)") + kA + "}} x"),
            "DIR/index.json: not the exporter's index: text after the JSON value (at byte 60)");
  EXPECT_EQ(check(R"({"materials": {"\udc00": {}}})"),
            "DIR/index.json: not the exporter's index: an unpaired surrogate in a \\u escape (at "
            "byte 16)");
}

TEST_F(StagedIndex, OtherShapesAreRefusedWithTheirByte) {
  const std::string prefix = "DIR/index.json: not the exporter's index: ";
  EXPECT_EQ(check("[]"), prefix + "expected '{' (at byte 0)");
  EXPECT_EQ(check("{}"), prefix + "no \"materials\" object (at byte 0)");
  EXPECT_EQ(check(R"({"materials": {}, "extra": 1})"),
            prefix + "unknown key \"extra\" (only \"materials\") (at byte 27)");
  EXPECT_EQ(check(R"({"materials": {}, "materials": {}})"),
            prefix + "\"materials\" given twice (at byte 31)");
  EXPECT_EQ(check(R"({"materials": []})"), prefix + "expected '{' (at byte 14)");
  EXPECT_EQ(check(std::string(R"({"materials": {)") + kA + ", " + kA + "}}"),
            prefix + "material \"A\" listed twice (at byte 64)");
  EXPECT_EQ(check(R"({"materials": {"A": "a.mgraph"}})"), prefix + "expected '{' (at byte 20)");
  EXPECT_EQ(check(R"({"materials": {"A": {"file": "a.mgraph", "colour": "red"}}})"),
            prefix + "unknown key \"colour\" (only \"file\" and \"material\") (at byte 51)");
  EXPECT_EQ(check(R"({"materials": {"A": {"file": 1, "material": "a"}}})"),
            prefix + "expected a string (at byte 29)");
  EXPECT_EQ(check(R"({"materials": {"A": {"file": "a.mgraph", "file": "b.mgraph"}}})"),
            prefix + "material \"A\" gives \"file\" twice (at byte 49)");
  EXPECT_EQ(check(R"({"materials": {"A": {"file": "a.mgraph"}}})"),
            prefix + "material \"A\" lacks \"file\" or \"material\" (at byte 20)");
  EXPECT_EQ(check(R"({"materials": {"A": {"file": "a.mgraph", "material": ""}}})"),
            prefix + "material \"A\" lacks \"file\" or \"material\" (at byte 20)");
}

TEST_F(StagedIndex, TheIndexNamesExactlyTheGraphsPresent) {
  EXPECT_EQ(check(R"({"materials": {"A": {"file": "a.mgraph", "material": "a"},
                     "C": {"file": "c.mgraph", "material": "c"}}})"),
            "DIR/index.json: names c.mgraph, which the export does not hold");
  EXPECT_EQ(check(std::string(R"({"materials": {)") + kA + "}}"),
            "DIR/b.mgraph: a graph that index.json does not name");
}

}  // namespace
}  // namespace memograph::cli
