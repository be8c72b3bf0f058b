// `memograph bake` through the CLI, as a user runs it (docs/guide/bake.md): values, pixel
// orientation of every format, --bounds, batches with a bad graph, usage errors, and that a
// failing material writes nothing. Images are tiny (a few pixels) so lavapipe is quick.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "runtime/host/image.h"
#include "runtime/materials/material_baker.h"
#include "tools/io/image_io.h"

namespace memograph {
namespace {

namespace fs = std::filesystem;
using testing::runCli;

class BakeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("memograph_bake_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "graphs");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string graph(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / "graphs" / (name + ".mgraph");
    std::ofstream(path) << text;
    return path.string();
  }
  std::string out() const { return (dir_ / "out").string(); }
  std::string outFile(const std::string& name) const { return (dir_ / "out" / name).string(); }

  // Every file in the output folder (temporaries included), sorted.
  std::vector<std::string> outputFiles() const {
    std::vector<std::string> names;
    if (!fs::exists(dir_ / "out"))
      return names;
    for (const auto& entry : fs::directory_iterator(dir_ / "out"))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  // The floats of a PFM in file order (after the header), and its size.
  static std::vector<float> rawPfm(const std::string& path, int& width, int& height) {
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    double scale = 0;
    in >> magic >> width >> height >> scale;
    in.get();
    EXPECT_EQ(magic, "PF");
    EXPECT_LT(scale, 0.0);  // little-endian
    std::vector<float> values(std::size_t(width) * height * 3);
    in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * 4));
    EXPECT_TRUE(in.good());
    return values;
  }

  fs::path dir_;
};

TEST_F(BakeCli, ConstantColourIsExactAndOnlyWrittenOutputsAreFiles) {
  const auto g = graph("Const",
                       "BaseColorOutput (0.25, 0.1, 0.75);\n"
                       "RoughnessOutput 0.3;\n"
                       "SpecularOutput 0.7;\n");
  const auto run = runCli("bake " + g + " --size 3x2 --out " + out() + " --format pfm");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("[1/1] Const ... ok"), std::string::npos) << run.output;
  EXPECT_EQ(outputFiles(), (std::vector<std::string>{"Const_baseColor.pfm", "Const_roughness.pfm",
                                                     "Const_specular.pfm"}));
  int w = 0, h = 0;
  const auto colour = rawPfm(outFile("Const_baseColor.pfm"), w, h);
  ASSERT_EQ(w, 3);
  ASSERT_EQ(h, 2);
  for (int p = 0; p < w * h; ++p) {
    EXPECT_EQ(colour[p * 3 + 0], 0.25f);
    EXPECT_EQ(colour[p * 3 + 1], 0.1f);  // float(0.1) exactly: no rounding on the way
    EXPECT_EQ(colour[p * 3 + 2], 0.75f);
  }
  const auto roughness = rawPfm(outFile("Const_roughness.pfm"), w, h);
  const auto specular = rawPfm(outFile("Const_specular.pfm"), w, h);
  for (std::size_t k = 0; k < roughness.size(); ++k) {
    EXPECT_EQ(roughness[k], 0.3f);  // grey: R = G = B
    EXPECT_EQ(specular[k], 0.7f);
  }
}

TEST_F(BakeCli, PrincipledOutputWritesSpecularWithBlendersDefault) {
  const auto set = graph("Set",
                         "PrincipledOutput BaseColor=(0.1, 0.2, 0.3) Specular=0.8 "
                         "SpecularTint=0.25 CyclesPrincipled=1;\n");
  const auto unset = graph("Unset", "PrincipledOutput BaseColor=(0.1, 0.2, 0.3);\n");
  const auto run = runCli("bake " + set + " " + unset + " --size 1x1 --format pfm --out " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(outputFiles(),
            (std::vector<std::string>{
                "Set_baseColor.pfm", "Set_cyclesPrincipled.pfm", "Set_emission.pfm",
                "Set_metallic.pfm", "Set_opacity.pfm", "Set_roughness.pfm", "Set_specular.pfm",
                "Set_specularTint.pfm", "Unset_baseColor.pfm", "Unset_cyclesPrincipled.pfm",
                "Unset_emission.pfm", "Unset_metallic.pfm", "Unset_opacity.pfm",
                "Unset_roughness.pfm", "Unset_specular.pfm", "Unset_specularTint.pfm"}));
  int w = 0, h = 0;
  EXPECT_EQ(rawPfm(outFile("Set_specular.pfm"), w, h)[0], 0.8f);
  EXPECT_EQ(rawPfm(outFile("Unset_specular.pfm"), w, h)[0], 0.5f);
  // Specular Tint and the Cycles weighting: as written, and off by default.
  EXPECT_EQ(rawPfm(outFile("Set_specularTint.pfm"), w, h)[0], 0.25f);
  EXPECT_EQ(rawPfm(outFile("Set_cyclesPrincipled.pfm"), w, h)[0], 1.0f);
  EXPECT_EQ(rawPfm(outFile("Unset_specularTint.pfm"), w, h)[0], 0.0f);
  EXPECT_EQ(rawPfm(outFile("Unset_cyclesPrincipled.pfm"), w, h)[0], 0.0f);
}

TEST_F(BakeCli, SpecularTintAndCyclesPrincipledSinksClampToZeroOne) {
  const auto g = graph("Sinks", "SpecularTintOutput 1.5;\nCyclesPrincipledOutput -2;\n");
  const auto run = runCli("bake " + g + " --size 1x1 --format pfm --out " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(outputFiles(),
            (std::vector<std::string>{"Sinks_cyclesPrincipled.pfm", "Sinks_specularTint.pfm"}));
  int w = 0, h = 0;
  EXPECT_EQ(rawPfm(outFile("Sinks_specularTint.pfm"), w, h)[0], 1.0f);
  EXPECT_EQ(rawPfm(outFile("Sinks_cyclesPrincipled.pfm"), w, h)[0], 0.0f);
}

TEST_F(BakeCli, NegativeAndLargeValuesSurviveFloatFormats) {
  const auto g = graph("Signed", "EmissionOutput Color=(-1.5, 2750.25, 1e-7) Strength=1.0;\n");
  for (const std::string format : {"pfm", "exr"}) {
    const auto run = runCli("bake " + g + " --size 2x2 --out " + out() + " --format " + format);
    ASSERT_EQ(run.exitCode, 0) << run.output;
  }
  int w = 0, h = 0;
  const auto pfm = rawPfm(outFile("Signed_emission.pfm"), w, h);
  EXPECT_EQ(pfm[0], -1.5f);
  EXPECT_EQ(pfm[1], 2750.25f);
  EXPECT_EQ(pfm[2], 1e-7f);
  compiler::Diagnostics diagnostics;
  const auto exr = io::readImageFloat(outFile("Signed_emission.exr"), diagnostics);
  ASSERT_TRUE(exr) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(exr->rgba[0], -1.5f);
  EXPECT_EQ(exr->rgba[1], 2750.25f);
  EXPECT_EQ(exr->rgba[2], 1e-7f);
}

// Pixel (i, j) is uv ((i + 0.5) / W, (j + 0.5) / H); j = 0 (v near 0) is the PFM's first
// stored row (Blender's img.pixels order) and the EXR's and PNG's last (top row first).
TEST_F(BakeCli, UvPixelCentresInTheDocumentedOrientation) {
  const auto g = graph("Uv",
                       "UVInput Out>0;\n"
                       "EmissionOutput Color<0;\n"
                       "BaseColorOutput In<0;\n");
  const int W = 4, H = 3;
  for (const std::string format : {"pfm", "exr", "png"}) {
    const auto run = runCli("bake " + g + " --size 4x3 --out " + out() + " --format " + format);
    ASSERT_EQ(run.exitCode, 0) << run.output;
  }
  int w = 0, h = 0;
  const auto pfm = rawPfm(outFile("Uv_emission.pfm"), w, h);
  ASSERT_EQ(w, W);
  ASSERT_EQ(h, H);
  for (int j = 0; j < H; ++j) {
    for (int i = 0; i < W; ++i) {
      const float* p = &pfm[(std::size_t(j) * W + i) * 3];
      EXPECT_FLOAT_EQ(p[0], (i + 0.5f) / W) << i << "," << j;
      EXPECT_FLOAT_EQ(p[1], (j + 0.5f) / H) << i << "," << j;
      EXPECT_EQ(p[2], 0.0f);
    }
  }
  // The project's PFM reader turns it into top-row-first, like the EXR.
  const auto read = runtime::readPfm(outFile("Uv_emission.pfm"));
  compiler::Diagnostics diagnostics;
  const auto exr = io::readImageFloat(outFile("Uv_emission.exr"), diagnostics);
  ASSERT_TRUE(exr) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(exr->width, std::uint32_t(W));
  ASSERT_EQ(exr->height, std::uint32_t(H));
  for (std::uint32_t y = 0; y < std::uint32_t(H); ++y) {
    for (std::uint32_t x = 0; x < std::uint32_t(W); ++x) {
      const float v = (float(H - 1 - y) + 0.5f) / H;  // row 0 of the file: the top, v near 1
      EXPECT_FLOAT_EQ(exr->pixel(x, y)[0], (x + 0.5f) / W);
      EXPECT_FLOAT_EQ(exr->pixel(x, y)[1], v);
      EXPECT_EQ(read.pixel(x, y)[1], exr->pixel(x, y)[1]);
    }
  }
  // PNG: the same orientation, colours sRGB-encoded.
  const auto png = io::readImageRgba8(outFile("Uv_baseColor.png"), diagnostics);
  ASSERT_TRUE(png) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(png->width, W);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const float v = (float(H - 1 - y) + 0.5f) / H;
      EXPECT_EQ(png->rgba[(std::size_t(y) * W + x) * 4 + 1], io::toSrgb8(v, io::LdrOptions{}));
    }
  }
}

TEST_F(BakeCli, PngScalarsAreLinearAndNormalsEncoded) {
  const auto g = graph("Png",
                       "RoughnessOutput 0.5;\n"
                       "NormalOutput (0.0, 0.0, 1.0);\n"
                       "BaseColorOutput (0.5, 0.5, 0.5);\n");
  const auto run = runCli("bake " + g + " --size 2x2 --out " + out() + " --format png");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  compiler::Diagnostics diagnostics;
  const auto roughness = io::readImageRgba8(outFile("Png_roughness.png"), diagnostics);
  const auto normal = io::readImageRgba8(outFile("Png_normal.png"), diagnostics);
  const auto colour = io::readImageRgba8(outFile("Png_baseColor.png"), diagnostics);
  ASSERT_TRUE(roughness && normal && colour) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(roughness->rgba[0], 128);  // linear 0.5
  EXPECT_EQ(normal->rgba[0], 128);     // 0.5 * 0 + 0.5
  EXPECT_EQ(normal->rgba[2], 255);     // 0.5 * 1 + 0.5
  EXPECT_EQ(colour->rgba[0], 188);     // sRGB of 0.5
}

// A node library of the real prelude and sinks plus test nodes reading the object-space
// inputs, so the test does not depend on the Blender nodes' sockets.
std::string objectSpaceLibrary(const fs::path& dir) {
  const fs::path nodes = dir / "nodes";
  fs::create_directories(nodes);
  fs::copy(fs::path(MEMOGRAPH_NODES_DIR) / "prelude", nodes / "prelude",
           fs::copy_options::recursive);
  fs::copy_file(fs::path(MEMOGRAPH_NODES_DIR) / "outputs.inc", nodes / "outputs.inc");
  std::ofstream(nodes / "object.inc") <<
      R"(// Test nodes: the object-space material inputs.

/// The object-space position.
/// @types T = float3, float3_D
/// @input objectPosition
void TestObject(in MaterialInputs inputs, out T Out) {
  mg_assign(inputs.objectPosition, Out);
}

/// Generated coordinates.
/// @types T = float3, float3_D
/// @input generated
void TestGenerated(in MaterialInputs inputs, out T Out) {
  mg_assign(inputs.generated, Out);
}

/// The generated coordinates' derivative along the footprint's first axis.
/// @input generated
void TestGeneratedDx(in MaterialInputs inputs, out float3 Out) {
  Out = inputs.generated.x;
}

/// The rest, packed: (backfacing + objectRandom, objectLocation.x, dot(geometricNormal, z)).
/// @input geometricNormal
/// @input objectLocation
/// @input objectRandom
/// @input backfacing
void TestRest(in MaterialInputs inputs, out float3 Out) {
  Out = float3(inputs.backfacing + inputs.objectRandom, inputs.objectLocation.x,
               inputs.geometricNormal.z);
}
)";
  return nodes.string();
}

TEST_F(BakeCli, BoundsSetObjectPositionAndGenerated) {
  const std::string nodes = objectSpaceLibrary(dir_);
  const auto g = graph("Space",
                       "TestObject Out>0;\n"
                       "EmissionOutput Color<0;\n"
                       "TestGenerated Out>1;\n"
                       "BaseColorOutput In<1;\n"
                       "TestRest Out>2;\n"
                       "NormalOutput In<2;\n");
  const int W = 4, H = 2;
  struct Case {
    std::string bounds;
    float lo[3], hi[3];
  };
  const Case cases[] = {
      {"", {-1, -1, 0}, {1, 1, 0}},  // Blender's default plane: (2u-1, 2v-1, 0)
      {"0,0,-1,4,2,3", {0, 0, -1}, {4, 2, 3}},
      {"-3,-1,2,1,1,2", {-3, -1, 2}, {1, 1, 2}},
      {"2,-1,0,2,1,0", {2, -1, 0}, {2, 1, 0}},  // zero width in x: size 1, Generated x 0.5
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.bounds);
    const auto run = runCli("bake " + g + " --nodes " + nodes + " --size 4x2 --format pfm --out " +
                            out() + (c.bounds.empty() ? "" : " --bounds " + c.bounds));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    int w = 0, h = 0;
    const auto object = rawPfm(outFile("Space_emission.pfm"), w, h);
    const auto generated = rawPfm(outFile("Space_baseColor.pfm"), w, h);
    for (int j = 0; j < H; ++j) {
      for (int i = 0; i < W; ++i) {
        const float uv[2] = {(i + 0.5f) / W, (j + 0.5f) / H};
        const std::size_t at = (std::size_t(j) * W + i) * 3;
        for (int k = 0; k < 3; ++k) {
          const float expected =
              k < 2 ? c.lo[k] + uv[k] * (c.hi[k] - c.lo[k]) : 0.5f * (c.lo[k] + c.hi[k]);
          EXPECT_NEAR(object[at + k], expected, 1e-6) << i << "," << j << " axis " << k;
          const float loc = 0.5f * (c.lo[k] + c.hi[k]);
          float size = 0.5f * (c.hi[k] - c.lo[k]);
          if (size == 0.0f)
            size = 1.0f;
          EXPECT_NEAR(generated[at + k], (expected - loc) / (2.0f * size) + 0.5f, 1e-6)
              << i << "," << j << " axis " << k;
        }
      }
    }
  }
  // The plane's constants: front face, random 0, object at the origin, normal +Z.
  int w = 0, h = 0;
  const auto rest = rawPfm(outFile("Space_normal.pfm"), w, h);
  EXPECT_EQ(rest[0], 0.0f);
  EXPECT_EQ(rest[1], 0.0f);
  EXPECT_EQ(rest[2], 1.0f);
}

// --normal tilts the shading normal over the whole plane (normalized), as a plane with
// custom normals in Blender; without it the normal is +Z.
TEST_F(BakeCli, NormalSetsTheShadingNormal) {
  const auto g = graph("Tilted",
                       "NormalInput Out>0;\n"
                       "EmissionOutput Color<0;\n");
  struct Case {
    std::string normal;
    float expected[3];
  };
  const Case cases[] = {
      {"", {0.0f, 0.0f, 1.0f}},
      {"1,-2,2", {1.0f / 3.0f, -2.0f / 3.0f, 2.0f / 3.0f}},
      {"0,0,-5", {0.0f, 0.0f, -1.0f}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.normal);
    const auto run = runCli("bake " + g + " --size 2x2 --format pfm --out " + out() +
                            (c.normal.empty() ? "" : " --normal " + c.normal));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    int w = 0, h = 0;
    const auto normal = rawPfm(outFile("Tilted_emission.pfm"), w, h);
    ASSERT_EQ(normal.size(), 2u * 2u * 3u);
    for (std::size_t at = 0; at < normal.size(); ++at)
      EXPECT_NEAR(normal[at], c.expected[at % 3], 1e-6f) << "value " << at;
  }
}

// Cycles' bake footprint: half a texel (averaged over x and y) along the diagonals.
TEST_F(BakeCli, GeneratedDerivativesFollowCyclesBakeFootprint) {
  const std::string nodes = objectSpaceLibrary(dir_);
  const auto g = graph("Footprint",
                       "TestGeneratedDx Out>0;\n"
                       "EmissionOutput Color<0;\n");
  const auto run = runCli("bake " + g + " --nodes " + nodes +
                          " --size 8x4 --format pfm --bounds 0,0,0,3,1,0 --out " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  int w = 0, h = 0;
  const auto dx = rawPfm(outFile("Footprint_emission.pfm"), w, h);
  // Texels are 3/8 by 1/4 world units: half a texel on average is 0.15625, and the
  // diagonal step (k, -k, 0) with k = 0.15625 / sqrt(2) maps to Generated through the
  // texture space's half size (1.5, 0.5, 1): (k / 3, -k, 0).
  const float k = 0.15625f * 0.70710678f;
  EXPECT_NEAR(dx[0], k / 3.0f, 1e-6f);
  EXPECT_NEAR(dx[1], -k, 1e-6f);
  EXPECT_EQ(dx[2], 0.0f);
}

TEST_F(BakeCli, FolderWithABadGraphBakesTheOthersAndFails) {
  graph("Alpha", "BaseColorOutput (1.0, 0.0, 0.0);\n");
  graph("Broken", "BaseColorOutput In<7;\nNoSuchNode 1.0;\n");
  graph("Gamma", "RoughnessOutput 0.25;\n");
  const auto run =
      runCli("bake " + (dir_ / "graphs").string() + " --size 2x2 --format pfm --out " + out());
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("[1/3] Alpha ... ok"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("[2/3] Broken ... failed"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Broken.mgraph:2:1: error"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("[3/3] Gamma ... ok"), std::string::npos) << run.output;
  EXPECT_EQ(outputFiles(),
            (std::vector<std::string>{"Alpha_baseColor.pfm", "Gamma_roughness.pfm"}));
}

TEST_F(BakeCli, AMaterialThatFailsWritesNothing) {
  // Compiles, but its texture is missing: the bake fails before any file is written.
  const auto g = graph("Textured",
                       "UVInput Out>0;\n"
                       "ImageTexture \"missing.png\" UV<0 Color>1 Alpha>2;\n"
                       "BaseColorOutput In<1;\n"
                       "RoughnessOutput 0.5;\n");
  const auto run = runCli("bake " + g + " --size 2x2 --out " + out());
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("missing.png"), std::string::npos) << run.output;
  EXPECT_TRUE(outputFiles().empty());
}

TEST_F(BakeCli, TexturesAreLoadedRelativeToTheGraph) {
  fs::copy(fs::path(MEMOGRAPH_EXAMPLES_DIR) / "textures", dir_ / "graphs" / "textures",
           fs::copy_options::recursive);
  const auto g = graph("Checker",
                       "UVInput Out>0;\n"
                       "ImageTexture \"textures/checker.png\" UV<0 Color>1 Alpha>2;\n"
                       "BaseColorOutput In<1;\n");
  const auto run = runCli("bake " + g + " --size 2x2 --format pfm --out " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(outputFiles(), (std::vector<std::string>{"Checker_baseColor.pfm"}));
}

TEST_F(BakeCli, UsageErrorsExitTwoAndWriteNothing) {
  const auto g = graph("Ok", "BaseColorOutput (1.0, 1.0, 1.0);\n");
  const std::string o = " --out " + out();
  const std::vector<std::string> bad = {
      "",                                          // nothing at all
      g + " --size 2x2",                           // no --out
      g + o,                                       // no --size
      "--size 2x2" + o,                            // no graph
      g + " --size 2by2" + o,                      // bad size
      g + " --size 0x2" + o,                       // empty size
      g + " --size 2x2 --format tiff" + o,         // bad format
      g + " --size 2x2 --bounds 1,2,3" + o,        // too few numbers
      g + " --size 2x2 --bounds 1,0,0,0,1,1" + o,  // min > max
      g + " --size 2x2 --bounds 0,0,0,1,1,x" + o,  // not a number
      g + " --size 2x2 --normal 0,0,0" + o,        // a zero normal
      g + " --size 2x2 --normal 1,2" + o,          // too few numbers
      g + " --size 2x2 --normal 1,x,0" + o,        // not a number
      g + " --size 2x2 --frobnicate" + o,          // unknown option
      g + " --size 2x2 --time 0" + o,              // no dispatch to time
      g + " --size 2x2 --time x" + o,              // not a number
      g + " --size 2x2 --time 1001" + o,           // past the bound
  };
  for (const auto& arguments : bad) {
    const auto run = runCli("bake " + arguments);
    EXPECT_EQ(run.exitCode, 2) << arguments << "\n" << run.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_EQ(runCli("bake --help").exitCode, 0);
}

// --time prints one line per material, the median of R dispatches in ns a pixel, which
// tools/bench/node_cost_graphs.py parses; it needs no --out and writes no file.
TEST_F(BakeCli, TimeReportsEachMaterialsMedianAndWritesNothing) {
  graph("Flat", "BaseColorOutput (1.0, 0.5, 0.25);\n");
  graph("Noisy",
        "UVInput Out>0;\n"
        "Separate2 Vector<0 X>1 Y>2;\n"
        "Combine3 X<1 Y<2 Z=0.5 Vector>3;\n"
        "NoiseTexture Vector<3 Detail=4 Color>4;\n"
        "BaseColorOutput In<4;\n");
  const auto run = runCli("bake " + (dir_ / "graphs").string() + " --size 8x8 --time 3");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const std::string name : {"Flat", "Noisy"}) {
    const std::string prefix = "time " + name + " ";
    const std::size_t at = run.output.find(prefix);
    ASSERT_NE(at, std::string::npos) << run.output;
    const double nsPerPixel = std::strtod(run.output.c_str() + at + prefix.size(), nullptr);
    EXPECT_GT(nsPerPixel, 0.0) << run.output;
    EXPECT_NE(run.output.find(" ns/pixel (median of 3 dispatches of 8x8)", at), std::string::npos)
        << run.output;
  }
  EXPECT_EQ(run.output.find("wrote "), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// --time keeps the GPU busy for about a quarter of a second before it times, so that its
// clocks are up (a graph timed right after its compile timed 2-5x slower or faster on an
// H100 from one call to the next).
TEST(BakeWarmUp, CoversAQuarterSecondWithinItsBounds) {
  EXPECT_EQ(runtime::bakeWarmUpDispatches(1e6), 250u);   // 1 ms a dispatch
  EXPECT_EQ(runtime::bakeWarmUpDispatches(3e6), 84u);    // rounded up
  EXPECT_EQ(runtime::bakeWarmUpDispatches(1e9), 1u);     // a dispatch longer than that
  EXPECT_EQ(runtime::bakeWarmUpDispatches(1e3), 4096u);  // at most 4096
  EXPECT_EQ(runtime::bakeWarmUpDispatches(0.0), 4096u);  // a probe that timed nothing
}

TEST_F(BakeCli, BoundsOutOfRangeAreNamedAsSuchNotAsMinOverMax) {
  const auto g = graph("Ok", "BaseColorOutput (1.0, 1.0, 1.0);\n");
  const std::string o = " --out " + out();
  const auto huge =
      runCli("bake " + g + " --size 2x2 --bounds -1e38,-1e38,-1e38,1e38,1e38,1e38" + o);
  EXPECT_EQ(huge.exitCode, 2) << huge.output;
  EXPECT_NE(huge.output.find("xmin -1e38 is out of range"), std::string::npos) << huge.output;
  EXPECT_EQ(huge.output.find("min <= max"), std::string::npos) << huge.output;
  const auto swapped = runCli("bake " + g + " --size 2x2 --bounds 1,0,0,0,1,1" + o);
  EXPECT_EQ(swapped.exitCode, 2) << swapped.output;
  EXPECT_NE(swapped.output.find("xmin is greater than xmax"), std::string::npos) << swapped.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(BakeCli, OutOnADanglingLinkSaysSo) {
  const auto g = graph("Ok", "BaseColorOutput (1.0, 1.0, 1.0);\n");
  fs::create_symlink(dir_ / "nowhere", dir_ / "out");
  const auto run = runCli("bake " + g + " --size 2x2 --format pfm --out " + out());
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("is a dangling symbolic link"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("File exists"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "nowhere"));
}

// A bake killed mid-write (SIGKILL) leaves its full-size temporaries; the next write into
// that folder removes those of processes that are gone, and nothing else.
TEST_F(BakeCli, TemporariesOfKilledWritersAreRemovedByTheNextWrite) {
  const pid_t dead = ::fork();
  if (dead == 0)
    ::_exit(0);
  ASSERT_GT(dead, 0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  fs::create_directories(dir_ / "out");
  const std::string deadPid = std::to_string(dead), livePid = std::to_string(::getpid());
  // This host's mark in a temporary's name (atomic_file.cpp: FNV-1a of the host name), and
  // another host's: a pid on another host (a farm's shared folder) is not ours to judge.
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  std::uint32_t hash = 2166136261u;
  for (const char* c = host; *c; ++c)
    hash = (hash ^ static_cast<unsigned char>(*c)) * 16777619u;
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", hash);
  const std::string here = hex,
                    elsewhere = std::string(here[0] == '0' ? "1" : "0") + here.substr(1);
  const std::vector<std::string> stale = {".Const_baseColor.partial-" + deadPid + "-a1B2c3.pfm",
                                          ".Other.partial-" + deadPid + "-zzzzzz",
                                          ".Lit.partial-" + deadPid + "@" + here + "-q1w2e3.pfm"};
  const std::vector<std::string> kept = {
      ".Const_baseColor.partial-" + livePid + "-a1B2c3.pfm",        // a live writer
      ".Other.partial-" + deadPid + "-zzzzzz.pfm.old",              // a commit's backup
      ".notes.partial-" + deadPid,                                  // not our naming
      "Other.partial-" + deadPid + "-zzzzzz.pfm",                   // not hidden
      ".Lit.partial-" + deadPid + "@" + elsewhere + "-q1w2e3.pfm",  // another host's writer
  };
  for (const auto& name : stale)
    std::ofstream(dir_ / "out" / name) << std::string(1000, 'x');
  for (const auto& name : kept)
    std::ofstream(dir_ / "out" / name) << "keep";
  const auto g = graph("Const", "BaseColorOutput (0.25, 0.1, 0.75);\n");
  const auto run = runCli("bake " + g + " --size 2x2 --format pfm --out " + out());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::vector<std::string> expected = kept;
  expected.push_back("Const_baseColor.pfm");
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(outputFiles(), expected);
}

}  // namespace
}  // namespace memograph
