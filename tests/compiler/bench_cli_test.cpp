// `memograph bench`'s options for the memoization sweeps: a frame stride is
// refused with a cache, --label names the per-frame file so variants do not collide, and
// --time-limit stops a run that would take too long and says so.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "cli_run.h"

namespace memograph {
namespace {

namespace fs = std::filesystem;

using testing::runCli;

// Each test gets a scratch folder (removed afterwards, failed assertions or not); a build
// without the renderer (no Vulkan SDK) has a bench that only says so, and skips.
class BenchCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (runCli("bench --help").exitCode != 0)
      GTEST_SKIP() << "this memograph has no renderer";
    directory_ = fs::temp_directory_path() /
                 ("memograph_bench_cli_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override {
    if (!directory_.empty())
      fs::remove_all(directory_);
  }
  std::string path(const std::string& name) const { return (directory_ / name).string(); }
  // The smallest run: the landscape at 16x9, one path of one bounce, its own shader cache,
  // free materials (these tests are about the bench's options; lavapipe compiles the
  // landscape's materials into the query shader for over a minute).
  std::string smallRun() const {
    return "bench builtin:landscape --size 16x9 --paths 1 --bounces 1 --floor-materials "
           "--shader-cache " +
           path("shaders");
  }
  // A summary CSV's header and first line.
  static std::pair<std::string, std::string> headerAndFirstLine(const std::string& csv) {
    std::ifstream in(csv);
    std::string header, line;
    std::getline(in, header);
    std::getline(in, line);
    return {header, line};
  }

  fs::path directory_;
};

TEST_F(BenchCliTest, FrameStrideWithACacheIsAUsageError) {
  const auto run = runCli("bench builtin:landscape --cache texel --frame-stride 10");
  EXPECT_EQ(run.exitCode, 2) << run.output;
  EXPECT_NE(run.output.find("--frame-stride needs --cache none"), std::string::npos) << run.output;
  EXPECT_EQ(runCli("bench builtin:landscape --frame-stride 0").exitCode, 2);
  EXPECT_EQ(runCli("bench builtin:landscape --static-camera --frame-stride 2").exitCode, 2);
  EXPECT_EQ(runCli("bench builtin:landscape --label 'a/b'").exitCode, 2);
}

TEST_F(BenchCliTest, LabelNamesThePerFrameFileAndTheCsvLine) {
  // The smallest strided run: 2 timed frames of a 4-camera path.
  const auto run = runCli(smallRun() + " --frames 2 --warmup 0 --frame-stride 2 --label floor_x2" +
                          " --csv " + path("summary.csv") + " --frames-csv " + path("f_"));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("landscape [floor_x2] 16x9"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(directory_ / "f_landscape_floor_x2_16x9.csv"));
  const auto [header, line] = headerAndFirstLine(path("summary.csv"));
  EXPECT_NE(header.find(",label,warmup,frame_stride,camera_frames,total_cache_hit_rate"),
            std::string::npos)
      << header;
  EXPECT_NE(line.find(",floor_x2,0,2,4,"), std::string::npos) << line;
}

// The cache's line says how its keys are refreshed (cacheRefreshText), the default included.
TEST_F(BenchCliTest, TheCacheLineSaysHowKeysAreRefreshed) {
  const auto byDefault = runCli(smallRun() + " --frames 1 --warmup 0 --cache texel");
  ASSERT_EQ(byDefault.exitCode, 0) << byDefault.output;
  EXPECT_NE(byDefault.output.find("keys refreshed: uv never, voxel every 16 frames"),
            std::string::npos)
      << byDefault.output;
  const auto given = runCli(smallRun() + " --frames 1 --warmup 0 --cache texel --cache-refresh 4");
  ASSERT_EQ(given.exitCode, 0) << given.output;
  EXPECT_NE(given.output.find("keys refreshed every 4 frames"), std::string::npos) << given.output;
}

// --time-limit stops a run after the frame that reaches it (here 0 s: after the first,
// a warm-up frame), reports what it covers and marks the CSV line; a bad value is a usage
// error. Without reaching the limit a run is complete (stopped_early 0).
TEST_F(BenchCliTest, TimeLimitStopsARunAndSaysSo) {
  const auto stopped =
      runCli(smallRun() + " --warmup 1 --frames 50 --time-limit 0 --csv " + path("stopped.csv"));
  ASSERT_EQ(stopped.exitCode, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("stopped by --time-limit 0 s after 1 of 51 frames (0 of 50 timed)"),
            std::string::npos)
      << stopped.output;
  const auto complete =
      runCli(smallRun() + " --warmup 1 --frames 2 --time-limit 3600 --csv " + path("complete.csv"));
  ASSERT_EQ(complete.exitCode, 0) << complete.output;
  EXPECT_EQ(complete.output.find("stopped by"), std::string::npos) << complete.output;
  const auto [header, stoppedLine] = headerAndFirstLine(path("stopped.csv"));
  EXPECT_TRUE(header.ends_with(",frames_requested,stopped_early")) << header;
  EXPECT_TRUE(stoppedLine.ends_with(",50,1")) << stoppedLine;
  EXPECT_TRUE(headerAndFirstLine(path("complete.csv")).second.ends_with(",2,0"));
  EXPECT_EQ(runCli("bench builtin:landscape --time-limit -1").exitCode, 2);
  EXPECT_EQ(runCli("bench builtin:landscape --time-limit soon").exitCode, 2);
}

// Every scene and every size is checked before any is measured: an empty --sizes item, an
// unknown or out-of-range second scene are usage errors (2) before the device is opened
// ("device: " starts a measurement's log).
TEST_F(BenchCliTest, EverySceneAndSizeIsCheckedBeforeAnyIsMeasured) {
  const std::pair<std::string, std::string> cases[] = {
      {"builtin:landscape --sizes 16x9,", "--sizes takes WxH[,WxH...], not '16x9,'"},
      {"builtin:landscape --sizes ,16x9", "a size is missing"},
      {"builtin:landscape --sizes 16x9,,8x8", "a size is missing"},
      {"builtin:landscape:terrain=8 builtin:bogus --sizes 8x8", "unknown built-in scene 'bogus'"},
      {"builtin:landscape:terrain=8 builtin:landscape:terrain=1 --sizes 8x8",
       "terrain (the landscape's terrain grid: cells per side) is an integer in 2..4096"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto run =
        runCli("bench " + arguments + " --frames 1 --warmup 0 --csv " + path("out.csv"));
    EXPECT_EQ(run.exitCode, 2) << arguments << ": " << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << arguments << ": " << run.output;
    EXPECT_EQ(run.output.find("device: "), std::string::npos) << arguments << ": measured first";
    EXPECT_FALSE(fs::exists(path("out.csv")));
  }
}

// No output over an input (the node library's files, through a link too) or over another
// output (--csv and a per-frame file): a usage error naming both, before anything runs.
TEST_F(BenchCliTest, OutputsOverInputsOrEachOtherAreRefused) {
  fs::create_directories(directory_ / "nodes" / "prelude");
  std::ofstream(directory_ / "nodes" / "prelude" / "common.inc") << "// kept\n";
  fs::create_symlink(directory_ / "nodes" / "prelude" / "common.inc", directory_ / "link.csv");
  const std::pair<std::string, std::string> cases[] = {
      {"--nodes " + path("nodes") + " --csv " + path("link.csv"),
       "--csv '" + path("link.csv") + "' is --nodes file"},
      {"--frames-csv " + path("f_") + " --csv " + path("f_landscape_16x9.csv"),
       "--csv '" + path("f_landscape_16x9.csv") + "': two outputs cannot share a file"},
      {"--csv " + path("a.csv") + " --pipeline-statistics " + path("a.csv"),
       "--pipeline-statistics '" + path("a.csv") + "' is --csv '" + path("a.csv") +
           "': two outputs cannot share a file"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto run = runCli("bench builtin:landscape --sizes 16x9 " + arguments);
    EXPECT_EQ(run.exitCode, 2) << arguments << ": " << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << arguments << ": " << run.output;
    EXPECT_EQ(run.output.find("device: "), std::string::npos) << arguments << ": measured first";
  }
  std::ifstream kept(directory_ / "nodes" / "prelude" / "common.inc");
  std::string line;
  std::getline(kept, line);
  EXPECT_EQ(line, "// kept");
}

// --pipeline-statistics: where the driver reports none (lavapipe), the run fails (1) naming
// the extension it lacks and writes no file, its --csv neither; where it reports them (the
// GPU machine), the file holds the header and the scene's pipelines.
TEST_F(BenchCliTest, PipelineStatisticsAreWrittenOrWhatTheDriverLacksIsNamed) {
  const auto run = runCli(smallRun() + " --frames 1 --warmup 0 --csv " + path("out.csv") +
                          " --pipeline-statistics " + path("statistics.csv"));
  if (run.exitCode == 1) {
    EXPECT_NE(run.output.find("lacks VK_KHR_pipeline_executable_properties"), std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(path("statistics.csv")));
    EXPECT_FALSE(fs::exists(path("out.csv")));
    return;
  }
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::ifstream in(path("statistics.csv"));
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "scene,pipeline,executable,statistic,value");
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line.rfind("landscape,", 0), 0u) << line;
}

}  // namespace
}  // namespace memograph
