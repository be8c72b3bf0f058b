// `memograph pack` through the CLI: a glTF scene with a textured graph and an environment
// image renders the same from its pack as from its files (one seed, lavapipe, a tiny size);
// bench measures a pack; damaged packs are refused with the file and offset, exit 1.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "tools/io/scene_export.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exitCode = -1;
  std::string output;
};

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

class ScenePackCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder a process: ctest runs these tests in parallel processes.
    dir_ = fs::temp_directory_path() / ("memograph_scene_pack_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "materials" / "textures");
    const fs::path graphs = MEMOGRAPH_EXAMPLES_DIR;
    fs::copy_file(graphs / "textured_checker.mgraph", dir_ / "materials" / "floor.mgraph");
    fs::copy_file(graphs / "textures" / "checker.png",
                  dir_ / "materials" / "textures" / "checker.png");
    fs::copy_file(graphs / "textures" / "bumps_normal.png", dir_ / "sky.png");
    runtime::Scene scene;
    runtime::Mesh quad;
    quad.name = "quad";
    quad.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    quad.normals.assign(4, {0, 1, 0});
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 2, 1, 0, 3, 2};
    scene.meshes = {quad};
    scene.materials = {{.name = "floor", .graphText = "unused"}};
    scene.instances = {{.mesh = 0, .material = 0}};
    scene.lights = {
        {.type = runtime::LightType::Point, .position = {0, 2, 0}, .intensity = {5, 5, 5}}};
    scene.camera = {.position = {0, 2, 3}, .target = {0, 0, 0}};
    compiler::Diagnostics diagnostics;
    ASSERT_TRUE(exportSceneGltf(scene, (dir_ / "scene.gltf").string(), diagnostics))
        << compiler::formatDiagnostics(diagnostics);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliRun run(const std::string& args) {
    const fs::path log = dir_ / "cli_output.txt";
    const char* cli = std::getenv("MEMOGRAPH_CLI") ? std::getenv("MEMOGRAPH_CLI") : MEMOGRAPH_CLI;
    const std::string command =
        "cd '" + dir_.string() + "' && '" + cli + "' " + args + " > '" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128, readAll(log)};
  }

  fs::path dir_;
};

constexpr const char* kRender = " --size 16x9 --frames 2 --paths 2 --seed 7 --no-shader-cache";

TEST_F(ScenePackCli, ARenderFromThePackEqualsTheRenderFromTheFiles) {
  const CliRun pack =
      run("pack scene.gltf --materials materials --environment sky.png --out scene.mgpack");
  ASSERT_EQ(pack.exitCode, 0) << pack.output;
  EXPECT_NE(pack.output.find("1 materials, 1 textures"), std::string::npos) << pack.output;
  const CliRun source = run(std::string("render scene.gltf --materials materials --environment "
                                        "sky.png --out source.pfm") +
                            kRender);
  ASSERT_EQ(source.exitCode, 0) << source.output;
  fs::remove_all(dir_ / "materials");  // the pack needs nothing beside it
  fs::remove(dir_ / "sky.png");
  const CliRun packed = run(std::string("render scene.mgpack --out packed.pfm") + kRender);
  ASSERT_EQ(packed.exitCode, 0) << packed.output;
  const std::string a = readAll(dir_ / "source.pfm"), b = readAll(dir_ / "packed.pfm");
  ASSERT_GT(a.size(), 16u * 9u * 12u);
  EXPECT_TRUE(a == b) << "the pack's render differs from the source's";
}

TEST_F(ScenePackCli, PackingTwiceGivesTheSameBytes) {
  ASSERT_EQ(run("pack scene.gltf --materials materials --out a.mgpack").exitCode, 0);
  fs::rename(dir_ / "materials", dir_ / "moved");
  ASSERT_EQ(run("pack scene.gltf --materials moved --out b.mgpack").exitCode, 0);
  EXPECT_TRUE(readAll(dir_ / "a.mgpack") == readAll(dir_ / "b.mgpack"));
}

TEST_F(ScenePackCli, BenchMeasuresAPack) {
  ASSERT_EQ(run("pack scene.gltf --materials materials --out scene.mgpack").exitCode, 0);
  const CliRun bench = run(
      "bench scene.mgpack --sizes 16x9 --frames 2 --warmup 1 --shader-cache shaders --cache texel");
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  EXPECT_NE(bench.output.find("scene 16x9 P="), std::string::npos) << bench.output;
  // The one material is uv-only: the texel cache can serve all of its cost.
  EXPECT_NE(bench.output.find("cached share 100 % of the estimated material cost (whole 100 %"),
            std::string::npos)
      << bench.output;
}

TEST_F(ScenePackCli, ADamagedPackIsRefusedWithTheFileAndOffset) {
  ASSERT_EQ(run("pack scene.gltf --materials materials --out scene.mgpack").exitCode, 0);
  const std::string bytes = readAll(dir_ / "scene.mgpack");
  std::ofstream(dir_ / "cut.mgpack", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const CliRun render = run("render cut.mgpack --out x.pfm --size 16x9");
  EXPECT_EQ(render.exitCode, 1);
  EXPECT_NE(render.output.find("cut.mgpack: offset "), std::string::npos) << render.output;
  EXPECT_NE(render.output.find("truncated"), std::string::npos) << render.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.pfm"));
  std::string flipped = bytes;
  flipped[flipped.size() - 3] ^= 1;
  std::ofstream(dir_ / "flipped.mgpack", std::ios::binary) << flipped;
  const CliRun bench = run("bench flipped.mgpack --size 16x9");
  EXPECT_EQ(bench.exitCode, 1);
  EXPECT_NE(bench.output.find("flipped.mgpack: offset 32: corrupt"), std::string::npos)
      << bench.output;
}

TEST_F(ScenePackCli, AnOutputThatIsNotAPackIsAUsageError) {
  const CliRun pack = run("pack scene.gltf --materials materials --out scene.gltf2");
  EXPECT_EQ(pack.exitCode, 2);
  EXPECT_NE(pack.output.find("--out must name a .mgpack file"), std::string::npos) << pack.output;
}

}  // namespace
}  // namespace memograph::io
