// planPathDispatches: a frame's paths split over trace dispatches, without a device. Every
// path of a pixel is traced by exactly one dispatch, only the first dispatch starts the
// frame's share of the mean, and LiPaC's feedback pipeline traces the counted paths (all of
// them unless the counting frame is split).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/trace/megakernel/path_dispatches.h"

namespace memograph::runtime {
namespace {

bool inRun(std::uint32_t path, std::uint32_t first, std::uint32_t count, std::uint32_t paths) {
  return (path + paths - first % paths) % paths < count;
}

TEST(PathDispatches, EveryPathIsTracedOnceInRunsOfTheAskedLength) {
  for (std::uint32_t paths = 1; paths <= 8; ++paths) {
    for (std::uint32_t runLength = 0; runLength <= paths + 1; ++runLength) {
      for (std::uint32_t counted = 1; counted <= paths; ++counted) {
        for (std::uint32_t index = 0; index < 3; ++index) {
          for (const bool counting : {false, true}) {
            for (const bool split : {false, true}) {
              SCOPED_TRACE("P " + std::to_string(paths) + ", run " + std::to_string(runLength) +
                           ", counted " + std::to_string(counted) + ", index " +
                           std::to_string(index) + (counting ? ", counting" : "") +
                           (split ? ", split" : ""));
              const CountedPaths c = countedPaths(paths, counted, index);
              const std::vector<PathDispatch> plan =
                  planPathDispatches(paths, runLength, counting, split, c);
              ASSERT_FALSE(plan.empty());
              const std::uint32_t longest = runLength == 0 ? paths : runLength;
              for (std::uint32_t path = 0; path < paths; ++path) {
                int traced = 0;
                bool feedback = false;
                for (const PathDispatch& d : plan) {
                  if (inRun(path, d.firstPath, d.pathCount, paths)) {
                    ++traced;
                    feedback = d.feedback;
                  }
                }
                EXPECT_EQ(traced, 1) << "path " << path;
                const bool isCounted = inRun(path, c.first, c.count, paths);
                EXPECT_EQ(feedback, counting && (!split || isCounted)) << "path " << path;
              }
              for (std::size_t i = 0; i < plan.size(); ++i) {
                EXPECT_EQ(plan[i].adds, i > 0) << "dispatch " << i;
                EXPECT_GE(plan[i].pathCount, 1u);
                EXPECT_LE(plan[i].pathCount, longest);
                EXPECT_LT(plan[i].firstPath, paths);
                const gpu::TraceDispatchPush push = plan[i].push();
                EXPECT_EQ(push.paths,
                          gpu::uvec4(plan[i].firstPath, plan[i].pathCount, i > 0 ? 1u : 0u, 0u));
              }
            }
          }
        }
      }
    }
  }
}

TEST(PathDispatches, PlansTheCityBenchmarksDispatches) {
  // P = 6 in one dispatch, in six, and a counting frame split: its five quiet paths, then
  // the counted one with the feedback.
  EXPECT_EQ(planPathDispatches(6, 0, false, false, {}).size(), 1u);
  EXPECT_EQ(planPathDispatches(6, 1, false, false, {}).size(), 6u);
  const std::vector<PathDispatch> split = planPathDispatches(6, 0, true, true, {3, 1});
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0].firstPath, 4u);
  EXPECT_EQ(split[0].pathCount, 5u);
  EXPECT_FALSE(split[0].feedback);
  EXPECT_EQ(split[1].firstPath, 3u);
  EXPECT_EQ(split[1].pathCount, 1u);
  EXPECT_TRUE(split[1].feedback);
  EXPECT_TRUE(split[1].adds);
  // Runs of 4: the five quiet paths in two dispatches, the counted one in a third.
  EXPECT_EQ(planPathDispatches(6, 4, true, true, {3, 1}).size(), 3u);
  // Nothing to split where every path counts.
  EXPECT_EQ(planPathDispatches(6, 0, true, true, {0, 6}).size(), 1u);
}

TEST(PathDispatches, CountedPathsAreTheShadersChoice) {
  // path_tracer.glsl: first = (counting frame * counted) % P; 0 or P and more: every path.
  EXPECT_EQ(countedPaths(6, 1, 7).first, 1u);
  EXPECT_EQ(countedPaths(6, 1, 7).count, 1u);
  EXPECT_EQ(countedPaths(6, 2, 2).first, 4u);
  EXPECT_EQ(countedPaths(6, 2, 2).count, 2u);
  EXPECT_EQ(countedPaths(6, 0, 5).first, 0u);
  EXPECT_EQ(countedPaths(6, 0, 5).count, 6u);
  EXPECT_EQ(countedPaths(6, 9, 5).count, 6u);
}

TEST(PathDispatches, ImpossiblePlansAreRefused) {
  EXPECT_THROW(planPathDispatches(0, 1, false, false, {}), std::invalid_argument);
  EXPECT_THROW(planPathDispatches(6, 1, true, true, {6, 1}), std::invalid_argument);
  EXPECT_THROW(planPathDispatches(6, 1, true, true, {0, 7}), std::invalid_argument);
  EXPECT_THROW(planPathDispatches(6, 1, true, false, {0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime
