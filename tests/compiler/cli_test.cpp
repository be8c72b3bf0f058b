// The memograph CLI as a user runs it: exit codes, messages, all-or-nothing output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "test_support.h"

namespace memograph {
namespace {

namespace fs = std::filesystem;

using testing::runCli;

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("memograph_cli_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string write(const std::string& name, const std::string& text) {
    const auto path = directory_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  std::string nodes() const {
    return std::string(" --nodes ") + MEMOGRAPH_TEST_DATA_DIR + "/nodes";
  }

  fs::path directory_;
};

TEST_F(CliTest, CompileWritesIncludesAndMetadataForEachTarget) {
  const auto graph = write("normals.mgraph", "NormalInput Out>1;\nColorOutput In<1;\n");
  const auto out = (directory_ / "out").string();
  const auto run = runCli("compile " + graph + " --target both -o " + out + nodes());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(out + "/normals.glsl"));
  EXPECT_TRUE(fs::exists(out + "/normals.hlsl"));
  EXPECT_TRUE(fs::exists(out + "/normals.json"));
  const auto glslOnly = runCli("compile " + graph + " --target=glsl -o " + out + "/g" + nodes());
  ASSERT_EQ(glslOnly.exitCode, 0) << glslOnly.output;
  EXPECT_TRUE(fs::exists(out + "/g/normals.glsl"));
  EXPECT_FALSE(fs::exists(out + "/g/normals.hlsl"));
}

TEST_F(CliTest, ABadGraphFailsWithLocationAndWritesNothingAtAll) {
  const auto good = write("good.mgraph", "NormalInput Out>1;\nColorOutput In<1;\n");
  const auto bad = write("bad.mgraph", "NormalInput Out>1;\nColourOutput In<1;\n");
  const auto out = (directory_ / "out").string();
  const auto run = runCli("compile " + good + " " + bad + " -o " + out + nodes());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("bad.mgraph:2:1: error: unknown node type 'ColourOutput'"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("nothing written"), std::string::npos);
  EXPECT_FALSE(fs::exists(out + "/good.glsl")) << "no partial output";
}

TEST_F(CliTest, UsageErrorsExitWithTwo) {
  EXPECT_EQ(runCli("").exitCode, 2);
  EXPECT_EQ(runCli("frobnicate").exitCode, 2);
  EXPECT_EQ(runCli("compile").exitCode, 2);
  const auto badTarget = runCli("compile x.mgraph --target spirv");
  EXPECT_EQ(badTarget.exitCode, 2);
  EXPECT_NE(badTarget.output.find("--target must be glsl, hlsl or both"), std::string::npos);
  EXPECT_EQ(runCli("compile x.mgraph --bogus").exitCode, 2);
  EXPECT_EQ(runCli("compile x.mgraph -o").exitCode, 2);
  EXPECT_EQ(runCli("check").exitCode, 2);
}

TEST_F(CliTest, EveryCommandHasHelp) {
  for (const char* command : {"compile", "check", "nodes", "bake", "render", "bench", "diff",
                              "selftest", "import-blender", "pack"}) {
    for (const char* flag : {" --help", " -h"}) {
      const auto run = runCli(std::string(command) + flag);
      EXPECT_EQ(run.exitCode, 0) << command << flag << run.output;
      EXPECT_NE(run.output.find("usage: memograph " + std::string(command)), std::string::npos)
          << command << flag;
    }
  }
  // A usage error wins over the help, wherever each stands.
  EXPECT_EQ(runCli("compile --help --frob").exitCode, 2);
  EXPECT_EQ(runCli("render --frob -h").exitCode, 2);
  const auto top = runCli("--help");
  EXPECT_EQ(top.exitCode, 0);
  EXPECT_NE(top.output.find("compile"), std::string::npos);
}

// import-blender's --materials takes the names up to the next option (ArgumentScanner::list).
TEST_F(CliTest, ImportBlenderMaterialsTakeTheNamesUpToTheNextOption) {
  const std::string blend = (directory_ / "nope.blend").string();
  // Both names are the option's, so the one positional is the .blend (which is missing: 1).
  const auto two = runCli("import-blender " + blend + " --out " + directory_.string() +
                          " --materials Wood Metal --verbose");
  EXPECT_EQ(two.exitCode, 1) << two.output;
  EXPECT_NE(two.output.find("nope.blend: no such file"), std::string::npos) << two.output;
  // With '=' it takes one name, so the next word is a second positional.
  const auto equals = runCli("import-blender " + blend + " --out " + directory_.string() +
                             " --materials=Wood Metal");
  EXPECT_EQ(equals.exitCode, 2) << equals.output;
  EXPECT_NE(equals.output.find("give exactly one .blend file"), std::string::npos);
  for (const char* empty : {" --materials", " --materials --verbose", " --materials="}) {
    const auto run = runCli("import-blender " + blend + " --out " + directory_.string() + empty);
    EXPECT_EQ(run.exitCode, 2) << empty;
    EXPECT_NE(run.output.find("option '--materials' needs a value"), std::string::npos)
        << empty << run.output;
  }
  EXPECT_EQ(runCli("import-blender " + blend + " --frob").exitCode, 2);
  EXPECT_EQ(runCli("import-blender " + blend + " --out").exitCode, 2);
}

TEST_F(CliTest, MissingAndUnreadableFilesAreClearErrors) {
  const auto run = runCli("compile " + (directory_ / "nope.mgraph").string() + nodes());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("nope.mgraph: error: no such file"), std::string::npos) << run.output;
  const auto dir = runCli("check " + directory_.string() + nodes());
  EXPECT_EQ(dir.exitCode, 1);
  EXPECT_NE(dir.output.find("is a folder, not a file"), std::string::npos) << dir.output;
}

TEST_F(CliTest, CheckPrintsEachLinksTypeAndDerivatives) {
  const auto graph = write("d.mgraph",
                           "UVInput UV>1;\nImageTexture \"a.png\" UV<1 Color>2;\n"
                           "BaseColorOutput Color<2;\n");
  const auto run = runCli("check " + graph + nodes());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("material d: 3 nodes, cacheable, derivatives used"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("link1     float2_D  deriv  UVInput.UV -> ImageTexture.UV"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("link2     float4    plain  ImageTexture.Color -> "
                            "BaseColorOutput.Color (as float3)"),
            std::string::npos)
      << run.output;
}

TEST_F(CliTest, NodesListsOverloadsAndSuggestsNames) {
  const auto run = runCli("nodes Mul" + nodes());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("Mul(float3_D A, float3_D B) -> float3_D Out"), std::string::npos);
  EXPECT_NE(run.output.find("in  A = 1.0"), std::string::npos) << run.output;
  const auto typo = runCli("nodes Mull" + nodes());
  EXPECT_EQ(typo.exitCode, 1);
  EXPECT_NE(typo.output.find("did you mean 'Mul'"), std::string::npos) << typo.output;
}

TEST_F(CliTest, DuplicateMaterialNamesAreRejected) {
  const auto a = write("a.mgraph", "material Same;\nNormalInput Out>1;\nColorOutput In<1;\n");
  const auto b = write("b.mgraph", "material Same;\nNormalInput Out>1;\nColorOutput In<1;\n");
  const auto run = runCli("compile " + a + " " + b + " -o " + directory_.string() + nodes());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.output.find("material 'Same' is also defined by"), std::string::npos);
}

TEST_F(CliTest, RenderReportsAMissingEnvironmentImageBeforeTouchingTheGpu) {
  const auto run =
      runCli("render builtin:landscape --environment " + (directory_ / "missing.exr").string() +
             " --out " + (directory_ / "x.pfm").string());
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("missing.exr"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(directory_ / "x.pfm"));
}

// The small city (40 buildings, 6 flags) renders as it is: `--backend auto` takes the
// pipeline with callables for its 14 graphs, which lavapipe compiles in seconds (one query
// shader holding all of them ran past 16 minutes). A bad scale or camera path is a usage
// error (exit 2), in render and in bench.
TEST_F(CliTest, TheSmallCityRendersWithTheDefaultBackend) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  const auto out = (directory_ / "city.pfm").string();
  const auto bad = runCli("render builtin:city:scale=2 --out " + out);
  EXPECT_EQ(bad.exitCode, 2) << bad.output;  // a usage error
  EXPECT_NE(bad.output.find("scale is a number in (0, 1]"), std::string::npos) << bad.output;
  for (const std::string& command : {"render builtin:city:scale=0.02,path=bogus --out " + out,
                                     std::string("bench builtin:city:path=bogus --sizes 16x9")}) {
    const auto badPath = runCli(command);
    EXPECT_EQ(badPath.exitCode, 2) << command << ": " << badPath.output;
    EXPECT_NE(badPath.output.find("path is street"), std::string::npos) << badPath.output;
  }
  const auto run = runCli(
      "render builtin:city:scale=0.02 --size 16x9 --paths 1 --bounces 2 "
      "--frames 1 --out " +
      out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("pipeline, callable materials"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(out));
}

// Bad culling options are usage errors (exit 2) naming the flag, before any rendering; a
// culled render of the small city writes its image, its statistics and its top view.
TEST_F(CliTest, CullingOptionsAreCheckedAndACulledRenderWritesItsTopView) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  const auto out = (directory_ / "city.pfm").string();
  const auto top = (directory_ / "city_top.pfm").string();
  const auto stats = (directory_ / "city.csv").string();
  const std::string render = "render builtin:city:scale=0.02 --out " + out;
  const std::pair<std::string, std::string> bad[] = {
      {" --culling all", "--culling takes none, frustum or lipac, not 'all'"},
      {" --culling lipac --hitbox-deactivate 30", "--hitbox-deactivate (30) must be below"},
      {" --culling lipac --hitbox-size -1", "--hitbox-size must be a positive number"},
      {" --culling frustum --low-frames x", "--low-frames takes a whole number, not 'x'"},
      {" --culling lipac --feedback-every x", "--feedback-every takes a whole number, not 'x'"},
      {" --culling lipac --culling-radius far", "--culling-radius takes a number, not 'far'"},
      {" --culling lipac --look-appearing -3", "--look-appearing takes a whole number, not '-3'"},
      {" --blas-budget 64", "they need --culling frustum or --culling lipac"},
      {" --blas-build-ms 2", "they need --culling frustum or --culling lipac"},
      {" --culling frustum --blas-build-ms -1", "--blas-build-ms must be in [0, 1e6]"},
      {" --culling frustum --blas-build-ms soon", "--blas-build-ms takes a number, not 'soon'"},
      {" --culling lipac --paths 6 --feedback-paths 4", "--feedback-paths 4 must divide"},
      // LiPaC's split feedback dispatch, counters after the trace, host instance fill and
      // looks are its behaviour, not options.
      {" --culling lipac --feedback-dispatch single", "unknown option '--feedback-dispatch'"},
      {" --culling lipac --hit-counters closest-hit", "unknown option '--hit-counters'"},
      {" --culling lipac --instance-fill gpu", "unknown option '--instance-fill'"},
      {" --culling lipac --looks off", "unknown option '--looks'"},
      {" --debug-culling " + top, "--debug-culling shows which instances culling keeps"},
  };
  for (const auto& [flags, message] : bad) {
    const auto run = runCli(render + flags);
    EXPECT_EQ(run.exitCode, 2) << flags << ": " << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << flags << ": " << run.output;
    EXPECT_FALSE(fs::exists(out));
  }
  const auto run = runCli(render +
                          " --size 16x9 --paths 1 --bounces 2 --frames 3 --floor-materials "
                          "--backend query --culling lipac --debug-culling " +
                          top + " --stats " + stats);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("culling lipac: last frame"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_GT(fs::file_size(top), 512u * 512u * 12u);  // a 512x512 RGB float PFM
  std::ifstream csv(stats);
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",culling,active_instances,"), std::string::npos) << header;
}

// Options the chosen modes leave unused are accepted (a script may pass one set of flags to
// every mode it measures), and each is named on stderr, so that a forgotten --culling lipac
// or --cache tile does not pass unnoticed; the options a mode uses are not named.
TEST_F(CliTest, OptionsTheModesLeaveUnusedAreNamed) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  const std::string render = "render builtin:landscape --size 8x8 --floor-materials --out " +
                             (directory_ / "landscape.pfm").string();
  const auto unused = runCli(render +
                             " --eviction lru --tile 4x4 --hitbox-size 20 --culling-radius 5 "
                             "--feedback-every 2");
  // The wavefront traces one path of every pixel a round: --dispatch-paths is the megakernel's.
  const auto wavefront = runCli(render + " --shading wavefront --dispatch-paths 1");
  ASSERT_EQ(wavefront.exitCode, 0) << wavefront.output;
  EXPECT_NE(wavefront.output.find("render: --dispatch-paths is ignored: it needs the megakernel"),
            std::string::npos)
      << wavefront.output;
  ASSERT_EQ(unused.exitCode, 0) << unused.output;
  for (const char* line : {"render: --hitbox-size is ignored: it needs --culling lipac",
                           "render: --feedback-every is ignored: it needs --culling lipac",
                           "render: --culling-radius is ignored: it needs --culling frustum",
                           "render: --eviction is ignored: it needs --cache texel or --cache tile",
                           "render: --tile is ignored: it needs --cache tile"})
    EXPECT_NE(unused.output.find(line), std::string::npos) << line << "\n" << unused.output;
  const auto used = runCli(
      render + " --cache texel --eviction lru --tile 4x4 --culling frustum --culling-radius 5");
  ASSERT_EQ(used.exitCode, 0) << used.output;
  EXPECT_NE(used.output.find("--tile is ignored: it needs --cache tile"), std::string::npos)
      << used.output;
  EXPECT_EQ(used.output.find("--eviction is ignored"), std::string::npos) << used.output;
  EXPECT_EQ(used.output.find("--culling-radius is ignored"), std::string::npos) << used.output;
}

// Bad cache option values are usage errors (exit 2), refused before any GPU work, and the
// message names the value and the choices.
TEST_F(CliTest, RenderAndBenchRefuseBadCacheOptionValues) {
  const std::string out = " --out " + (directory_ / "x.pfm").string();
  for (const std::string& command : {"render builtin:landscape" + out, std::string("bench")}) {
    const auto format = runCli(command + " --value-format fp8");
    EXPECT_EQ(format.exitCode, 2) << format.output;
    EXPECT_NE(format.output.find("--value-format takes fp32 or fp16, not 'fp8'"), std::string::npos)
        << format.output;
    const auto clock = runCli(command + " --clock x");
    EXPECT_EQ(clock.exitCode, 2) << clock.output;
    EXPECT_NE(clock.output.find("--clock takes counter or frame, not 'x'"), std::string::npos)
        << clock.output;
    // The clock's shift and the read check are the cache's, not the command line's.
    for (const std::string removed : {"--clock-shift", "--cache-read-check"}) {
      const auto run = runCli(command + " --cache texel " + removed + " 1");
      EXPECT_EQ(run.exitCode, 2) << run.output;
      EXPECT_NE(run.output.find("unknown option '" + removed + "'"), std::string::npos)
          << run.output;
    }
    const auto filter = runCli(command + " --cache texel --cache-filter bilinear");
    EXPECT_EQ(filter.exitCode, 2) << filter.output;
    EXPECT_NE(
        filter.output.find("--cache-filter takes nearest, trilinear or stochastic, not 'bilinear'"),
        std::string::npos)
        << filter.output;
    // The tile cache filters with --filter.
    const auto tileFilter = runCli(command + " --cache tile --cache-filter trilinear");
    EXPECT_EQ(tileFilter.exitCode, 2) << tileFilter.output;
    EXPECT_NE(tileFilter.output.find("is the texel cache's"), std::string::npos)
        << tileFilter.output;
    const auto keys = runCli(command + " --cache texel --cache-keys uv,voxel");
    EXPECT_EQ(keys.exitCode, 2) << keys.output;
    EXPECT_NE(keys.output.find("--cache-keys takes all, or uv, object and world"),
              std::string::npos)
        << keys.output;
    const auto probe = runCli(command + " --floor-materials --cache texel --probe 17");
    EXPECT_EQ(probe.exitCode, 2) << probe.output;
    const auto device = runCli(command + " --device x");  // shared renderer options
    EXPECT_EQ(device.exitCode, 2) << device.output;
    EXPECT_NE(device.output.find("--device takes a device index"), std::string::npos)
        << device.output;
    const auto dispatch = runCli(command + " --dispatch-paths two");
    EXPECT_EQ(dispatch.exitCode, 2) << dispatch.output;
    EXPECT_NE(dispatch.output.find("--dispatch-paths takes a number of paths per trace "
                                   "dispatch (0: all in one), not 'two'"),
              std::string::npos)
        << dispatch.output;
  }
  EXPECT_EQ(runCli("render builtin:landscape --debug-misses" + out).exitCode, 2);
  EXPECT_FALSE(fs::exists(directory_ / "x.pfm"));
}

// The shader and pipeline caches are optimisations. An entry that cannot be written (here
// their folder is a file; a full disk is
// ShaderCache.AnUnwritableEntryIsAWarningAndLeavesNoTemporary in tests/runtime, since a file-size
// limit also breaks lavapipe's file-backed memory) is a warning, and the render goes on.
TEST_F(CliTest, RenderGoesOnWhenTheShaderCacheCannotBeWritten) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  const auto cache = write("cache", "a file where the cache folder would be\n");
  // One triangle (tests/adversarial/make_scenes.py's valid.gltf): one shader, seconds.
  const auto scene = write("triangle.gltf",
                           R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)"
                           R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}]})");
  const auto out = (directory_ / "x.png").string();
  const auto run = runCli("render " + scene + " --size 8x8 --paths 1 --bounces 1 --frames 1 " +
                          "--shader-cache " + cache + " --out " + out);
  if (run.output.find("this build") != std::string::npos)
    GTEST_SKIP() << "this memograph reads no scene files or writes no PNG: " << run.output;
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("warning: cannot write the shader cache entry"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("warning: cannot write the pipeline cache"), std::string::npos)
      << run.output;
  EXPECT_TRUE(fs::exists(out));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(directory_))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"cache", "triangle.gltf", "x.png"}));
}

// --help lists the common options in sections, each in at most two lines of at most 100
// columns, in at most 100 lines; --help-all adds the advanced ones.
TEST_F(CliTest, RenderAndBenchHelpListTheCommonOptionsAndHelpAllTheRest) {
  if (runCli("bench --help").output.find("this build") != std::string::npos)
    GTEST_SKIP() << "this memograph has no renderer";
  for (const std::string command : {"render", "bench"}) {
    const auto help = runCli(command + " --help");
    const auto all = runCli(command + " --help-all");
    ASSERT_EQ(help.exitCode, 0) << help.output;
    ASSERT_EQ(all.exitCode, 0) << all.output;
    EXPECT_LE(std::count(help.output.begin(), help.output.end(), '\n'), 100) << help.output;
    for (const char* option : {"--cache", "--snap-uv", "--floor-materials", "--culling",
                               "--shading", "Material memoization", "--help-all"})
      EXPECT_NE(help.output.find(option), std::string::npos) << command << " " << option;
    for (const char* option : {"--value-format", "--eviction", "--clock", "--tile-storage",
                               "--cache-secondary-only", "--cache-filter", "--look-appearing",
                               "--blas-budget", "--dispatch-paths", "--wavefront-paths"}) {
      EXPECT_EQ(help.output.find(option), std::string::npos) << command << " " << option;
      EXPECT_NE(all.output.find(option), std::string::npos) << command << " " << option;
    }
    std::istringstream lines(all.output);
    std::string option;
    int optionLines = 0;
    for (std::string line; std::getline(lines, line);) {
      EXPECT_LE(line.size(), 100u) << line;
      if (line.rfind("  -", 0) == 0) {
        option = line;
        optionLines = 1;
      } else if (line.rfind("    ", 0) == 0) {
        EXPECT_LE(++optionLines, 2) << option;
      }
    }
  }
  EXPECT_NE(runCli("render --help").output.find("--debug-misses"), std::string::npos);
}

// docs/guide/cli.md is the CLI reference: it holds every command's help word for word
// (`render` and `bench` with --help-all; tools/make_cli_reference.py writes them), so a changed
// default or help line must reach it, and it names every render and bench option.
TEST_F(CliTest, TheCliReferenceHoldsEveryCommandsHelp) {
  if (runCli("bench --help").output.find("this build") != std::string::npos)
    GTEST_SKIP() << "this memograph has no renderer";
  std::ifstream file(std::string(MEMOGRAPH_EXAMPLES_DIR) + "/../docs/guide/cli.md");
  ASSERT_TRUE(file) << "docs/guide/cli.md";
  const std::string reference((std::istreambuf_iterator<char>(file)), {});
  for (const std::string command :
       {"compile", "check", "nodes", "bake", "diff", "import-blender", "pack", "selftest"}) {
    const std::string help = runCli(command + " --help").output;
    EXPECT_NE(reference.find(help), std::string::npos)
        << "docs/guide/cli.md does not hold `memograph " << command
        << " --help` as printed (python3 tools/make_cli_reference.py build/tools/memograph)";
  }
  int options = 0;
  for (const std::string command : {"render", "bench"}) {
    const std::string help = runCli(command + " --help-all").output;
    EXPECT_NE(reference.find(help), std::string::npos)
        << "docs/guide/cli.md does not hold `memograph " << command << " --help-all` as printed";
    std::istringstream lines(help);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("  --", 0) != 0)
        continue;
      const std::string name = line.substr(2, line.find_first_of(" ,", 2) - 2);
      ++options;
      EXPECT_NE(reference.find("`" + name), std::string::npos)
          << "docs/guide/cli.md lacks " << command << " " << name;
    }
  }
  EXPECT_GT(options, 60);
}

// The tile cache's give-up test hook is an environment variable, not an option; a bad value
// is a usage error naming it.
TEST_F(CliTest, TheTileGiveUpTestHookIsAnEnvironmentVariable) {
  if (runCli("bench --help").output.find("this build") != std::string::npos)
    GTEST_SKIP() << "this memograph has no renderer";
  const std::string render =
      "render builtin:landscape --cache tile --out " + (directory_ / "x.pfm").string();
  const auto option = runCli(render + " --test-give-up 60");
  EXPECT_EQ(option.exitCode, 2) << option.output;
  EXPECT_NE(option.output.find("unknown option '--test-give-up'"), std::string::npos)
      << option.output;
  for (const char* bad : {"101", "x", "-5"}) {
    ::setenv("MEMOGRAPH_TEST_TILE_GIVE_UP", bad, 1);
    const auto run = runCli(render);
    ::unsetenv("MEMOGRAPH_TEST_TILE_GIVE_UP");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("MEMOGRAPH_TEST_TILE_GIVE_UP takes a whole number of percent, "
                              "0..100, not '" +
                              std::string(bad) + "'"),
              std::string::npos)
        << run.output;
  }
  EXPECT_FALSE(fs::exists(directory_ / "x.pfm"));
}

TEST_F(CliTest, RandomBytesNeverCrashTheCompiler) {
  std::string bytes;
  std::uint32_t state = 12345;
  for (int i = 0; i < 4096; ++i) {
    state = state * 1664525u + 1013904223u;
    bytes += static_cast<char>(state >> 24);
  }
  const auto graph = write("noise.mgraph", bytes);
  const auto run = runCli("compile " + graph + " -o " + directory_.string() + nodes());
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("noise.mgraph:1:"), std::string::npos);
}

// `material 1abc;` once read as a node named `material` with a bad number.
TEST_F(CliTest, AMaterialNameThatIsNotANameIsReportedAsABadName) {
  const auto graph = write("m.mgraph", "material 1abc;\nNormalInput Out>1;\nColorOutput In<1;\n");
  const auto run = runCli("check " + graph + nodes());
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("m.mgraph:1:10: error: '1abc' is not a valid material name"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("finite number"), std::string::npos) << run.output;
}

// The name names the output files: check must refuse what compile cannot write, and compile
// must refuse it before it creates the output folder.
TEST_F(CliTest, AMaterialNameTooLongForAFileNameFailsCheckAndCompileAlike) {
  const auto graph = write("long.mgraph", "material " + std::string(100'000, 'x') +
                                              ";\nNormalInput Out>1;\nColorOutput In<1;\n");
  const auto check = runCli("check " + graph + nodes());
  EXPECT_EQ(check.exitCode, 1) << check.output.substr(0, 2000);
  EXPECT_NE(check.output.find("long.mgraph:1:10: error: the material name is 100000 characters "
                              "long, over the limit of 200"),
            std::string::npos)
      << check.output.substr(0, 2000);
  const auto out = directory_ / "out";
  const auto compile = runCli("compile " + graph + " -o " + out.string() + nodes());
  EXPECT_EQ(compile.exitCode, 1) << compile.output.substr(0, 2000);
  EXPECT_NE(compile.output.find("over the limit of 200"), std::string::npos)
      << compile.output.substr(0, 2000);
  EXPECT_FALSE(fs::exists(out)) << "the output folder must not be created";
  const auto fits = write("fits.mgraph", "material " + std::string(200, 'x') +
                                             ";\nNormalInput Out>1;\nColorOutput In<1;\n");
  const auto written = runCli("compile " + fits + " -o " + out.string() + nodes());
  EXPECT_EQ(written.exitCode, 0) << written.output;
  EXPECT_TRUE(fs::exists(out / (std::string(200, 'x') + ".glsl")));
}

TEST_F(CliTest, AnEmptyTexturePathIsItsOwnError) {
  const auto graph = write("t.mgraph",
                           "UVInput UV>1;\nImageTexture Image=\"\" UV<1 Color>2;\n"
                           "BaseColorOutput In<2;\n");
  for (const std::string command : {"check ", "compile "}) {
    const auto run = runCli(command + graph + " -o " + (directory_ / "out").string() + nodes());
    EXPECT_EQ(run.exitCode, command == "check " ? 2 : 1) << run.output;
    if (command == "check ")
      continue;  // check takes no -o: that usage error is not what this test is about
    EXPECT_NE(run.output.find("t.mgraph:2:20: error: input 'Image' of 'ImageTexture' has an "
                              "empty texture path"),
              std::string::npos)
        << run.output;
    EXPECT_EQ(run.output.find("is a folder"), std::string::npos) << run.output;
  }
  const auto check = runCli("check " + graph + nodes());
  EXPECT_EQ(check.exitCode, 1) << check.output;
  EXPECT_NE(check.output.find("has an empty texture path"), std::string::npos) << check.output;
}

// Every option is validated (exit 2) before the output folder is looked at (exit 1).
TEST_F(CliTest, CompileReportsABadOptionValueBeforeABadOutputFolder) {
  const auto graph = write("g.mgraph", "NormalInput Out>1;\nColorOutput In<1;\n");
  const auto file = write("not_a_folder", "x");
  const auto missingNodes =
      runCli("compile " + graph + " -o " + file + " --nodes " + (directory_ / "missing").string());
  EXPECT_EQ(missingNodes.exitCode, 2) << missingNodes.output;
  EXPECT_NE(missingNodes.output.find("--nodes " + (directory_ / "missing").string() +
                                     ": the node library directory does not exist"),
            std::string::npos)
      << missingNodes.output;
  EXPECT_EQ(missingNodes.output.find("is not a folder"), std::string::npos) << missingNodes.output;
  const auto fileAsNodes = runCli("compile " + graph + " -o " + file + " --nodes " + file);
  EXPECT_EQ(fileAsNodes.exitCode, 2) << fileAsNodes.output;
  const auto checkNodes = runCli("check " + graph + " --nodes " + file);
  EXPECT_EQ(checkNodes.exitCode, 2) << checkNodes.output;
  EXPECT_EQ(fs::file_size(file), 1u);
}

// A diagnostic shows a window of a long line, not the line: a one-line graph of megabytes
// once printed (and held) a full copy of it per error.
TEST_F(CliTest, AnErrorOnAHugeLineShowsAWindowOfIt) {
  std::string line = "Float1Constant 0.5 ";
  for (int i = 0; i < 200'000; ++i)
    line += "Out>" + std::to_string(i) + " ";
  const auto graph = write("wide.mgraph", line + "junk@;\n");
  const auto run = runCli("check " + graph + nodes());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_LT(run.output.size(), 20'000u) << run.output.substr(0, 2000);
  EXPECT_NE(run.output.find("wide.mgraph:1:"), std::string::npos) << run.output.substr(0, 2000);
}

// Output over input, device range, order of checks: render and selftest.
constexpr const char* kSmallestRender = " --size 4x4 --paths 1 --bounces 1 --floor-materials";

// A shell command's exit code and output (its stdout), for runs that redirect otherwise
// than runCli: stderr alone, or under `timeout`.
testing::CliRun runShell(const std::string& command) {
  testing::CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return run;
  std::array<char, 4096> buffer;
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
    run.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}
// The CLI with stdout into `stdoutFile` and stderr alone in the output.
testing::CliRun runCliStderrOnly(const std::string& arguments, const std::string& stdoutFile) {
  return runShell(std::string(MEMOGRAPH_CLI) + " " + arguments + " 2>&1 >" + stdoutFile);
}

// A command never writes over a file it reads or one output over another, however the two
// are named (the same path spelled otherwise, a symbolic link, a hard link): a usage error
// naming both, before anything is read or rendered.
TEST_F(CliTest, RenderRefusesAnOutputThatIsOneOfItsInputs) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  const std::string camera = write("camera.txt", "0 1 5  0 0 0  60\n");
  const std::string scene = write("scene.gltf", "{}");
  const std::string environment = write("sky.exr", "not read");
  fs::create_directories(directory_ / "materials");
  const std::string graph = write("materials/Wood.mgraph", "material Wood;\n");
  fs::create_symlink(camera, directory_ / "camera_link.csv");
  fs::create_symlink(graph, directory_ / "graph_link.pfm");
  fs::create_hard_link(camera, directory_ / "camera_hard.csv");
  fs::create_directories(directory_ / "sub");
  const std::string out = (directory_ / "x.pfm").string(), dir = directory_.string() + "/";
  const std::pair<std::string, std::string> cases[] = {
      {"builtin:landscape --camera-path " + camera + " --stats " + dir + "camera_link.csv",
       "--stats '" + dir + "camera_link.csv' is --camera-path '" + camera + "'"},
      {"builtin:landscape --camera-path " + camera + " --stats " + dir + "camera_hard.csv",
       "is --camera-path"},
      {scene + " --stats " + scene, "--stats '" + scene + "' is SCENE"},
      {"builtin:landscape --environment " + environment + " --stats " + environment,
       "is --environment"},
      {scene + " --materials " + dir + "materials --debug-culling " + dir +
           "graph_link.pfm --culling frustum",
       "is --materials graph '" + graph + "'"},
      {"builtin:landscape --stats " + dir + "sub/../x.pfm",
       "is --out '" + out + "': two outputs cannot share a file"},
  };
  for (const auto& [arguments, message] : cases) {
    // The smallest render, should a check let one through.
    const auto run = runCli("render " + arguments + " --out " + out + kSmallestRender);
    EXPECT_EQ(run.exitCode, 2) << arguments << ": " << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << arguments << ": " << run.output;
    EXPECT_FALSE(fs::exists(out)) << arguments;
  }
  std::ifstream kept(camera);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "0 1 5  0 0 0  60\n");
  EXPECT_TRUE(fs::is_symlink(directory_ / "graph_link.pfm"));
}

// `--device N` past the last device is a usage error (2): the command line names a device
// this machine lacks, and the message says how many there are and lists them. Checked
// before any output or GPU work, in render and bench alike.
TEST_F(CliTest, ADevicePastTheLastIsAUsageErrorThatCountsTheDevices) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  if (runCli("render --list-devices").output.find("[0]") == std::string::npos)
    GTEST_SKIP() << "no Vulkan device: the renderer's own message applies";
  const auto out = (directory_ / "x.pfm").string();
  for (const std::string& command : {"render builtin:landscape --out " + out + " --device 999",
                                     std::string("bench --sizes 16x9 --device 999")}) {
    const auto run = runCli(command);
    EXPECT_EQ(run.exitCode, 2) << command << ": " << run.output;
    EXPECT_NE(run.output.find("--device 999 is out of range: this machine has "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("Vulkan device"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("[0] "), std::string::npos) << run.output;  // the listing
    EXPECT_EQ(run.output.find("device: "), std::string::npos) << "bench measured first";
  }
  EXPECT_FALSE(fs::exists(out));
}

// A command line with a usage error and a missing output folder is a usage error (2),
// whichever comes first on it: the formats, the built-in scene's values and the options'
// fitness for the shading are checked before the folders.
TEST_F(CliTest, RenderUsageErrorsComeBeforeTheOutputFolders) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  const auto missing = (directory_ / "missing" / "x.pfm").string();
  const std::pair<std::string, std::string> cases[] = {
      {"builtin:landscape:terrain=1 --out " + missing,
       "terrain (the landscape's terrain grid: cells per side) is an integer in 2..4096"},
      {"builtin:landscape --out " + missing + " --culling frustum --debug-culling " +
           (directory_ / "top.txt").string(),
       "--debug-culling must name a .pfm, .png or .exr file"},
      {"builtin:landscape --shading wavefront --floor-materials --cache texel --out " + missing,
       "the free-material floor has none"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto run = runCli("render " + arguments + kSmallestRender);
    EXPECT_EQ(run.exitCode, 2) << arguments << ": " << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << arguments << ": " << run.output;
  }
}

// Too few iterations for the tile fill's given-up tiles to publish anything is a usage
// error before any GPU work, on stderr with the minimum; stdout (the log) stays empty. So
// are the other bad values.
TEST_F(CliTest, SelftestRefusesTooFewIterationsOnStderr) {
  const std::string stdoutFile = (directory_ / "stdout.txt").string();
  for (const std::string arguments : {"--invocations 64 --iterations 4", "--iterations 0",
                                      "--invocations 100", "--rounds 0", "extra"}) {
    const auto run = runCliStderrOnly("selftest " + arguments, stdoutFile);
    EXPECT_EQ(run.exitCode, 2) << arguments << ": " << run.output;
    EXPECT_NE(run.output.find("memograph selftest: "), std::string::npos) << run.output;
    EXPECT_EQ(fs::file_size(stdoutFile), 0u) << arguments;
  }
  const auto tooFew = runCliStderrOnly("selftest --iterations 4", stdoutFile);
  EXPECT_NE(tooFew.output.find("give --iterations 6 or more"), std::string::npos) << tooFew.output;
}

// Two outputs in one folder, the folder spelled two ways ("D" and "D/sub/.."): the set is
// written (the folder locked once; a second lock on it waited forever), and the render ends.
TEST_F(CliTest, OutputsInOneFolderSpelledTwoWaysAreWritten) {
  if (runCli("bench --help").exitCode != 0)
    GTEST_SKIP() << "this memograph has no renderer";
  fs::create_directories(directory_ / "sub");
  const std::string image = (directory_ / "x.pfm").string(),
                    stats = (directory_ / "sub" / ".." / "x.csv").string();
  // `timeout` ends a hang with exit 124 instead of stalling the suite.
  const auto run = runShell("timeout 600 " + std::string(MEMOGRAPH_CLI) +
                            " render builtin:landscape:terrain=8 --out " + image + " --stats " +
                            stats + kSmallestRender + " 2>&1");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(image));
  EXPECT_TRUE(fs::exists(directory_ / "x.csv"));
}

// compile names its outputs after the materials: a graph file named like one (Foo.json for
// material Foo) would be replaced by its own metadata. Refused as a usage error, the input kept.
TEST_F(CliTest, CompileRefusesAnOutputThatIsOneOfItsInputs) {
  const std::string text = "material Foo;\nNormalInput Out>1;\nColorOutput In<1;\n";
  const auto graph = write("Foo.json", text);
  const auto run = runCli("compile " + graph + " -o " + directory_.string() + nodes());
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("an input: writing it would destroy what is read"), std::string::npos)
      << run.output;
  std::ifstream kept(graph);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(kept)), {}), text);
}

}  // namespace
}  // namespace memograph
