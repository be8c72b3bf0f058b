// Unit tests of the hardening pieces: the one output-writing path
// (runtime/host/atomic_file.h), the bounded input reader (compiler/input_file.h) and the glTF
// pre-check (tools/io/gltf_precheck.h). The CLI-level tests are run_corpus.py and
// concurrency_test.py beside this file.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "compiler/input_file.h"
#include "runtime/host/atomic_file.h"
#include "runtime/host/image.h"
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

// One triangle whose buffer is the file `uri` beside the glTF (tests/adversarial/
// make_scenes.py writes the same scenes for the CLI).
std::string externalTriangle(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "buffers": [{"byteLength": 44, "uri": ")" +
         uri + R"("}]})";
}
std::string triangleBuffer(std::uint16_t lastIndex) {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, lastIndex, 0};
  std::string bytes(reinterpret_cast<const char*>(positions), sizeof positions);
  bytes.append(reinterpret_cast<const char*>(indices), sizeof indices);
  return bytes;
}

// Vertex indices in an external .bin were not read, so assimp dropped a triangle
// with a bad one without a word; a missing buffer file was assimp's vaguer error.
TEST_F(Hardening, ExternalBufferIndicesAreChecked) {
  fs::create_directories(path("sub"));
  std::ofstream(path("sub/good.bin"), std::ios::binary) << triangleBuffer(2);
  std::ofstream(path("sub/bad.bin"), std::ios::binary) << triangleBuffer(60000);
  std::ofstream(path("sub/short.bin"), std::ios::binary) << triangleBuffer(2).substr(0, 20);
  std::ofstream(path("good.gltf")) << externalTriangle("sub/good.bin");
  std::ofstream(path("escaped.gltf")) << externalTriangle("sub\\/good.bin");
  std::ofstream(path("bad.gltf")) << externalTriangle("sub/bad.bin");
  std::ofstream(path("missing.gltf")) << externalTriangle("sub/missing.bin");
  std::ofstream(path("short.gltf")) << externalTriangle("sub/short.bin");
  std::ofstream(path("folder.gltf")) << externalTriangle("sub");
  std::ofstream(path("absolute.gltf")) << externalTriangle(path("sub/good.bin"));
  auto check = [&](const std::string& name) {
    compiler::Diagnostics diagnostics;
    const bool ok = io::precheckGltf(path(name), diagnostics);
    const std::string text = compiler::formatDiagnostics(diagnostics);
    EXPECT_EQ(ok, !diagnostics.hasErrors()) << text;
    return ok ? std::string("ok") : text;
  };
  EXPECT_EQ(check("good.gltf"), "ok");
  EXPECT_EQ(check("escaped.gltf"), "ok");  // "sub\/good.bin" is JSON for sub/good.bin
  EXPECT_NE(check("bad.gltf")
                .find("meshes[0].primitives[0].indices: index 2 is 60000, out of "
                      "range: the primitive has 3 vertices"),
            std::string::npos)
      << check("bad.gltf");
  EXPECT_NE(
      check("missing.gltf")
          .find("buffers[0].uri 'sub/missing.bin': " + path("sub") + "/missing.bin: no such file"),
      std::string::npos)
      << check("missing.gltf");
  EXPECT_NE(check("short.gltf").find("has 20 bytes, fewer than the buffer's byteLength of 44"),
            std::string::npos)
      << check("short.gltf");
  EXPECT_NE(check("folder.gltf").find("is a folder"), std::string::npos) << check("folder.gltf");
  EXPECT_NE(check("absolute.gltf").find("is an absolute path"), std::string::npos)
      << check("absolute.gltf");
}

// Found by memograph_gltf_import_fuzzer: assimp 5.2 allocates a base64 payload's decoded
// size, then throws on a byte over 127 without freeing it (and decodes other strangers as
// zeros). Data URIs are checked as assimp splits them; valid ones (escaped '/' included) pass.
TEST(GltfPrecheck, DataUrisMustBeBase64AsAssimpReadsThem) {
  auto check = [](const std::string& uri) {
    const std::string json = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 3,
        "uri": ")" + uri + R"("}], "images": [{"uri": "data:image/png;base64,AAAA"}]})";
    compiler::Diagnostics diagnostics;
    const bool ok = io::precheckGltfBytes("data.gltf", json, false, diagnostics);
    return ok ? std::string("ok") : compiler::formatDiagnostics(diagnostics);
  };
  EXPECT_EQ(check("data:application/octet-stream;base64,AAA/"), "ok");
  EXPECT_EQ(check("data:application/octet-stream;base64,AA=="), "ok");
  EXPECT_NE(check("data:application/octet-stream;base64,AA\u00ffA")
                .find("buffers[0].uri: the base64 data has a character that is not base64 (0xc3 at "
                      "character 2)"),
            std::string::npos)
      << check("data:application/octet-stream;base64,AA\u00ffA");
  EXPECT_NE(check("data:application/octet-stream;base64,AA=A").find("not base64"),
            std::string::npos);
  EXPECT_NE(check("data:application/octet-stream;base64,AAAAA").find("not a whole number"),
            std::string::npos);
  EXPECT_NE(check("data:application/" + std::string(120, 'x') + ";base64,AAAA").find("over 100"),
            std::string::npos);
  EXPECT_EQ(check("data:application/octet-stream,anything goes"), "ok");  // not base64
}

// The JSON reader's refusals reach the message with the byte of the JSON they are at.
TEST(GltfPrecheck, InvalidJsonNamesTheByteOfTheJson) {
  compiler::Diagnostics diagnostics;
  EXPECT_FALSE(io::precheckGltfBytes("bad.gltf", R"({"asset": {"version": "2.0\ud800"}})", false,
                                     diagnostics));
  EXPECT_NE(compiler::formatDiagnostics(diagnostics)
                .find("invalid glTF JSON: an unpaired surrogate in a \\u escape (at byte 26 of "
                      "the JSON)"),
            std::string::npos)
      << compiler::formatDiagnostics(diagnostics);
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
