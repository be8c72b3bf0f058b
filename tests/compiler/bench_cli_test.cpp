// `memograph bench`'s options for the memoization sweeps (issue 4): a frame stride is
// refused with a cache, and --label names the per-frame file so variants do not collide.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"

namespace memograph {
namespace {

namespace fs = std::filesystem;

using testing::runCli;

// A build without the renderer (no Vulkan SDK) has a bench that only says so.
bool benchAvailable() {
  return runCli("bench --help").exitCode == 0;
}

TEST(BenchCliTest, FrameStrideWithACacheIsAUsageError) {
  if (!benchAvailable())
    GTEST_SKIP() << "this memograph has no renderer";
  const auto run = runCli("bench builtin:landscape --cache texel --frame-stride 10");
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("--frame-stride needs --cache none"), std::string::npos) << run.output;
  EXPECT_EQ(runCli("bench builtin:landscape --frame-stride 0").exitCode, 2);
  EXPECT_EQ(runCli("bench builtin:landscape --static-camera --frame-stride 2").exitCode, 2);
  EXPECT_EQ(runCli("bench builtin:landscape --label 'a/b'").exitCode, 2);
}

TEST(BenchCliTest, LabelNamesThePerFrameFileAndTheCsvLine) {
  if (!benchAvailable())
    GTEST_SKIP() << "this memograph has no renderer";
  const fs::path directory =
      fs::temp_directory_path() / ("memograph_bench_cli_" + std::to_string(::getpid()));
  fs::remove_all(directory);
  fs::create_directories(directory);
  // The smallest strided run: 2 timed frames of a 4-camera path.
  const auto run = runCli(
      "bench builtin:landscape --size 16x9 --paths 1 --bounces 1 --frames 2 "
      "--warmup 0 --frame-stride 2 --label floor_x2 --csv " +
      (directory / "summary.csv").string() + " --frames-csv " + (directory / "f_").string() +
      " --shader-cache " + (directory / "shaders").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("landscape [floor_x2] 16x9"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(directory / "f_landscape_floor_x2_16x9.csv"));
  std::ifstream summary(directory / "summary.csv");
  std::string header, line;
  std::getline(summary, header);
  std::getline(summary, line);
  EXPECT_NE(header.find(",label,warmup,frame_stride,camera_frames,total_cache_hit_rate"),
            std::string::npos)
      << header;
  EXPECT_NE(line.find(",floor_x2,0,2,4,"), std::string::npos) << line;
  fs::remove_all(directory);
}

}  // namespace
}  // namespace memograph
