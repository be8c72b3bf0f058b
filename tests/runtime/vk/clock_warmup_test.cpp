// The clock warm-up keeps the device busy for the time asked, in submissions that grow, and
// leaves the device usable.
#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/vk/clock_warmup.h"

namespace memograph::runtime {
namespace {

TEST(ClockWarmup, RunsForTheTimeAskedAndLeavesTheDeviceUsable) {
  VulkanContext context(testing::testOptions().context);
  ClockWarmup warmup(context, {});
  // Timed from the run alone: the pass's creation would fill the 40 ms by itself.
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t submissions = warmup.run(std::chrono::milliseconds(40));
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(elapsed, std::chrono::milliseconds(40));
  EXPECT_GE(submissions, 1u);
  // Run again, as a render does after its second frame's pipelines: one submission at least,
  // of the length the first run grew to.
  EXPECT_GE(warmup.run(std::chrono::milliseconds(0)), 1u);
  EXPECT_TRUE(context.validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
