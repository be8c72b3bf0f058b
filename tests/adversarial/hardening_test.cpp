// Unit tests of the hardening pieces (issue 14): the one output-writing path
// (runtime/atomic_file.h), the bounded input reader (compiler/input_file.h) and the glTF
// pre-check (tools/io/gltf_precheck.h). The CLI-level tests are run_corpus.py and
// concurrency_test.py beside this file.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "compiler/input_file.h"
#include "runtime/atomic_file.h"
#include "runtime/image.h"
#include "tools/io/gltf_precheck.h"

namespace memograph {
namespace {

namespace fs = std::filesystem;

class Hardening : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("memograph-hardening-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

TEST_F(Hardening, WriteFileAtomicallyReplacesAndLeavesNoTemporary) {
  std::string error;
  ASSERT_TRUE(files::writeFileAtomically(path("a.txt"), "one", error)) << error;
  ASSERT_TRUE(files::writeFileAtomically(path("a.txt"), "two", error)) << error;
  EXPECT_EQ(read(path("a.txt")), "two");
  EXPECT_EQ(listing(), std::vector<std::string>{"a.txt"});
  struct stat info {};
  ASSERT_EQ(::stat(path("a.txt").c_str(), &info), 0);
  EXPECT_NE(info.st_mode & 0044, 0u) << "mkstemp's 0600 must not reach the output";
}

TEST_F(Hardening, FileSetRollsBackWhenARenameFailsPartWay) {
  std::string error;
  ASSERT_TRUE(files::writeFileSet({{path("a.glsl"), "old a"}, {path("b.glsl"), "old b"}}, error));
  fs::create_directories(path("c.json"));  // its rename fails: a folder is in the way
  EXPECT_FALSE(files::writeFileSet({{path("a.glsl"), "new a"},
                                    {path("b.glsl"), "new b"},
                                    {path("new.glsl"), "new"},
                                    {path("c.json"), "new c"}},
                                   error));
  EXPECT_NE(error.find("c.json"), std::string::npos) << error;
  EXPECT_EQ(error.find("Success"), std::string::npos) << error;
  EXPECT_EQ(read(path("a.glsl")), "old a");
  EXPECT_EQ(read(path("b.glsl")), "old b");
  EXPECT_FALSE(fs::exists(path("new.glsl")));
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.glsl", "b.glsl", "c.json"}));
}

TEST_F(Hardening, OutputPathsAreCheckedUpFront) {
  std::string error;
  EXPECT_TRUE(files::checkOutputPath(path("x.png"), error));
  EXPECT_FALSE(files::checkOutputPath(dir_, error));
  EXPECT_NE(error.find("folder"), std::string::npos);
  EXPECT_FALSE(files::checkOutputPath(path("missing/x.png"), error));
  EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
  EXPECT_EQ(files::errnoMessage("cannot write", 0), "cannot write: unknown error");
}

TEST_F(Hardening, InputsAreRegularFilesWithinTheLimit) {
  std::string error;
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  EXPECT_FALSE(files::readInputFile(path("fifo"), 100, "graphs", error));
  EXPECT_NE(error.find("FIFO"), std::string::npos) << error;
  EXPECT_FALSE(files::readInputFile("/dev/zero", 100, "graphs", error));
  EXPECT_NE(error.find("character device"), std::string::npos) << error;
  std::ofstream(path("big")) << std::string(101, 'x');
  EXPECT_FALSE(files::readInputFile(path("big"), 100, "graphs", error));
  EXPECT_NE(error.find("over the limit of 100 bytes for graphs"), std::string::npos) << error;
  EXPECT_EQ(files::readInputFile(path("big"), 101, "graphs", error).value(), std::string(101, 'x'));
  fs::create_symlink("l2", path("l1"));
  fs::create_symlink("l1", path("l2"));
  EXPECT_FALSE(files::readInputFile(path("l1"), 100, "graphs", error));
  EXPECT_NE(error.find("symbolic link loop"), std::string::npos) << error;
  EXPECT_FALSE(files::readInputFile(path("missing"), 100, "graphs", error));
  EXPECT_EQ(error, "no such file");
}

TEST_F(Hardening, PfmHeadersCannotDeclareMoreThanTheFileHolds) {
  std::string error;
  std::ofstream(path("big.pfm"), std::ios::binary) << "PF\n8000 8000\n-1.0\n"
                                                   << std::string(64, '\0');
  EXPECT_FALSE(runtime::tryReadPfm(path("big.pfm"), error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  runtime::HdrImage image{2, 1, std::vector<float>(8, 0.25f)};
  ASSERT_TRUE(runtime::tryWritePfm(path("ok.pfm"), image, error)) << error;
  EXPECT_EQ(runtime::tryReadPfm(path("ok.pfm"), error).value().rgba[0], 0.25f);
  EXPECT_EQ(listing(), (std::vector<std::string>{"big.pfm", "ok.pfm"}));
}

TEST(GltfPrecheck, TheShowcaseScenePasses) {
  compiler::Diagnostics diagnostics;
  EXPECT_TRUE(io::precheckGltf(MEMOGRAPH_EXAMPLES_DIR "/scenes/showcase.gltf", diagnostics))
      << compiler::formatDiagnostics(diagnostics);
}

TEST(GltfPrecheck, DeepHierarchiesAndHugeChunksAreRefused) {
  std::string json = R"({"asset": {"version": "2.0"}, "nodes": [)";
  for (int i = 0; i < 5000; ++i)
    json += R"({"children": [)" + std::to_string(i + 1) + "]},";
  json += "{}]}";
  compiler::Diagnostics diagnostics;
  EXPECT_FALSE(io::precheckGltfBytes("deep.gltf", json, false, diagnostics));
  EXPECT_NE(compiler::formatDiagnostics(diagnostics).find("over the limit of 1000"),
            std::string::npos);
  std::string glb = "glTF";
  auto u32 = [&](std::uint32_t v) {
    for (int b = 0; b < 4; ++b)
      glb.push_back(char(v >> (8 * b)));
  };
  u32(2);
  u32(24);           // the file's true length
  u32(0xFFFFFFF0u);  // a 4 GiB JSON chunk
  u32(0x4E4F534Au);
  glb += "{}  ";
  compiler::Diagnostics glbDiagnostics;
  EXPECT_FALSE(io::precheckGltfBytes("huge.glb", glb, true, glbDiagnostics));
  EXPECT_NE(compiler::formatDiagnostics(glbDiagnostics).find("4294967280"), std::string::npos);
}

}  // namespace
}  // namespace memograph
