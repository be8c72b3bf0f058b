// `memograph diff`: the printed statistics, the error map, and the exit codes (0 compared,
// 1 unreadable image or size mismatch, 2 usage error).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "cli_run.h"
#include "runtime/host/image.h"
#include "tools/io/image_io.h"

namespace fs = std::filesystem;

namespace memograph {
namespace {

using testing::CliRun;
using testing::runCli;

// The value printed after `label` at the start of a line ("mean  0.012345").
double statistic(const std::string& output, const std::string& label) {
  const auto at = output.find("\n" + label + " ");
  if (at == std::string::npos)
    return -1.0;
  return std::stod(output.substr(at + label.size() + 2));
}

class DiffCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("memograph_diff_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
    // A smooth reference; the test copy has a bright 4x4 square in the middle.
    runtime::HdrImage reference{kSize, kSize, std::vector<float>(kSize * kSize * 4, 1.0f)};
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        float* p = reference.pixel(x, y);
        p[0] = 0.1f + 0.5f * x / kSize;
        p[1] = 0.2f;
        p[2] = 0.1f + 0.5f * y / kSize;
      }
    runtime::HdrImage test = reference;
    for (int y = 14; y < 18; ++y)
      for (int x = 14; x < 18; ++x)
        test.pixel(x, y)[0] = test.pixel(x, y)[1] = test.pixel(x, y)[2] = 1.0f;
    runtime::HdrImage small{8, 8, std::vector<float>(8 * 8 * 4, 0.5f)};
    compiler::Diagnostics diagnostics;
    ASSERT_TRUE(io::writeImage(path("ref.png"), reference, {}, diagnostics));
    ASSERT_TRUE(io::writeImage(path("copy.png"), reference, {}, diagnostics));
    ASSERT_TRUE(io::writeImage(path("ref.exr"), reference, {}, diagnostics));
    ASSERT_TRUE(io::writeImage(path("test.png"), test, {}, diagnostics));
    ASSERT_TRUE(io::writeImage(path("small.png"), small, {}, diagnostics));
    std::ofstream(path("broken.png")) << "not a png";
    runtime::writePfm(path("ref.pfm"), reference);
    runtime::writePfm(path("test.pfm"), test);
    runtime::HdrImage withNan = reference;
    withNan.pixel(3, 5)[1] = std::numeric_limits<float>::quiet_NaN();
    runtime::writePfm(path("nan.pfm"), withNan);
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string path(const std::string& name) const { return (directory_ / name).string(); }
  std::string diff(const std::string& a, const std::string& b, const std::string& options = "") {
    return "diff " + path(a) + " " + path(b) + (options.empty() ? "" : " " + options);
  }

  static constexpr int kSize = 32;
  fs::path directory_;
};

// Every run costs the binary's start-up (~0.3 s, OpenImageIO's initialisation), and every
// test its own process under ctest, so the cases are grouped and kept few.

TEST_F(DiffCliTest, ComparesImagesAndWritesErrorMaps) {
  // Identical images: exactly zero, at the paper's default viewing conditions.
  CliRun run = runCli(diff("ref.png", "copy.png"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(statistic(run.output, "mean"), 0.0) << run.output;
  EXPECT_EQ(statistic(run.output, "max"), 0.0) << run.output;
  EXPECT_NE(run.output.find("67.02 pixels per degree"), std::string::npos) << run.output;

  // A bright square: statistics in order, and a magma map, dark where nothing changed.
  run = runCli(diff("ref.png", "test.png", "--out " + path("map.png")));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const double mean = statistic(run.output, "mean"), max = statistic(run.output, "max");
  EXPECT_GT(mean, 0.0);
  EXPECT_LT(mean, 0.2);
  EXPECT_GT(max, 0.5);
  EXPECT_LE(statistic(run.output, "p50"), statistic(run.output, "p90"));
  EXPECT_LE(statistic(run.output, "p90"), statistic(run.output, "p99"));
  EXPECT_LE(statistic(run.output, "p99"), max);
  compiler::Diagnostics diagnostics;
  const auto map = io::readImageRgba8(path("map.png"), diagnostics);
  ASSERT_TRUE(map);
  ASSERT_EQ(map->width, kSize);
  ASSERT_EQ(map->height, kSize);
  auto brightness = [&](int x, int y) {
    const auto* p = &map->rgba[(static_cast<std::size_t>(y) * kSize + x) * 4];
    return p[0] + p[1] + p[2];
  };
  EXPECT_LT(brightness(1, 1), 20);
  EXPECT_GT(brightness(16, 16), 300);

  // The EXR map holds the raw error as grey; twice the paper's distance is twice its ppd.
  run = runCli(diff("ref.png", "test.png", "--out " + path("map.exr") + " --monitor-distance 1.4"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("134.04 pixels per degree"), std::string::npos) << run.output;
  const auto raw = io::readImageFloat(path("map.exr"), diagnostics);
  ASSERT_TRUE(raw);
  EXPECT_NEAR(raw->pixel(16, 16)[0], statistic(run.output, "max"), 0.05);
  EXPECT_EQ(raw->pixel(16, 16)[0], raw->pixel(16, 16)[2]);

  // ref.exr holds the linear colours ref.png encodes: the sRGB one is decoded, and only the
  // PNG's 8-bit rounding differs, a faint difference everywhere (qc = 0.7 lifts it).
  run = runCli(diff("ref.png", "ref.exr"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_GT(statistic(run.output, "mean"), 0.0);
  EXPECT_LT(statistic(run.output, "mean"), 0.03);
}

// The renderer's PFM output is compared with the core's reader and the map written with its
// writer: the path the GPU bundle (built without OpenImageIO) takes.
TEST_F(DiffCliTest, ComparesPfmRendersAndWritesAPfmMap) {
  CliRun run = runCli(diff("ref.pfm", "ref.pfm"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(statistic(run.output, "mean"), 0.0) << run.output;

  run = runCli(diff("ref.pfm", "test.pfm", "--out " + path("map.pfm")));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_GT(statistic(run.output, "mean"), 0.0) << run.output;
  const runtime::HdrImage map = runtime::readPfm(path("map.pfm"));
  ASSERT_EQ(map.width, std::uint32_t(kSize));
  EXPECT_GT(map.pixel(15, 15)[0], 0.1f);  // inside the bright square
  EXPECT_EQ(map.pixel(0, 0)[0], 0.0f);
  EXPECT_EQ(map.pixel(15, 15)[0], map.pixel(15, 15)[2]);  // grey
}

TEST_F(DiffCliTest, BadImagesExitWithOne) {
  CliRun run = runCli(diff("ref.png", "small.png"));
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("differ in size"), std::string::npos) << run.output;
  run = runCli(diff("broken.png", "missing.png", "--out " + path("map.png")));
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("broken.png"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("missing.png"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("map.png")));
  // A NaN pixel is named, not averaged into `mean nan`.
  run = runCli(diff("ref.pfm", "nan.pfm"));
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("nan.pfm: error: pixel (3, 5) is not a finite number (NaN)"),
            std::string::npos)
      << run.output;
}

TEST_F(DiffCliTest, UsageErrorsExitWithTwo) {
  EXPECT_EQ(runCli("diff " + path("ref.png")).exitCode, 2);
  EXPECT_EQ(runCli(diff("ref.png", "test.png", "--ppd 40 --monitor-width 0.5")).exitCode, 2);
  EXPECT_EQ(runCli(diff("ref.png", "test.png", "--ppd -3")).exitCode, 2);
  // The CSF filter's cost grows with ppd: 1e7 once ran 83 s and 1e12 crashed.
  for (const char* observer : {"--ppd 1e12", "--ppd 1e7", "--ppd 1001", "--ppd 0.5",
                               "--monitor-distance 1e10", "--monitor-resolution 1e-3"}) {
    const CliRun run = runCli(diff("ref.png", "test.png", observer));
    EXPECT_EQ(run.exitCode, 2) << observer << "\n" << run.output;
    EXPECT_NE(run.output.find("outside 1 to 1000"), std::string::npos) << run.output;
  }
  EXPECT_EQ(runCli(diff("ref.png", "test.png", "--out " + path("map.tif"))).exitCode, 2);
  const CliRun help = runCli("diff --help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.output.find("LDR-FLIP"), std::string::npos);
}

// `diff A B --out A` would replace A with the error map. An output that is an
// input is a usage error, however it is named: the same path, another spelling of it, a
// symbolic link to it, a hard link to it; the input is left as it was.
TEST_F(DiffCliTest, RefusesAnErrorMapOverEitherInput) {
  fs::create_symlink(path("ref.pfm"), path("link.pfm"));
  fs::create_hard_link(path("test.pfm"), path("hard.pfm"));
  fs::create_directories(directory_ / "sub");
  const auto referenceBytes = fs::file_size(path("ref.pfm")),
             testBytes = fs::file_size(path("test.pfm"));
  const std::pair<std::string, std::string> outputs[] = {
      {path("ref.pfm"), "is REFERENCE"},
      {path("test.pfm"), "is TEST"},
      {(directory_ / "sub" / ".." / "ref.pfm").string(), "is REFERENCE"},
      {path("link.pfm"), "is REFERENCE"},
      {path("hard.pfm"), "is TEST"},
  };
  for (const auto& [out, role] : outputs) {
    const CliRun run = runCli(diff("ref.pfm", "test.pfm", "--out " + out));
    EXPECT_EQ(run.exitCode, 2) << out << ": " << run.output;
    EXPECT_NE(run.output.find("--out '" + out + "' " + role), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("mean"), std::string::npos) << "compared before refusing";
  }
  EXPECT_EQ(fs::file_size(path("ref.pfm")), referenceBytes);
  EXPECT_EQ(fs::file_size(path("test.pfm")), testBytes);
  EXPECT_TRUE(fs::is_symlink(path("link.pfm")));
  EXPECT_FLOAT_EQ(runtime::readPfm(path("ref.pfm")).pixel(0, 0)[0], 0.1f);  // still the image
}

}  // namespace
}  // namespace memograph
