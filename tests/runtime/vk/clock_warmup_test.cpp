// The clock warm-up keeps the device busy for the time asked, in submissions that grow, and
// leaves the device usable.
#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/vk/clock_warmup.h"

namespace memograph::runtime {
namespace {

TEST(ClockWarmup, RunsForTheTimeAskedAndLeavesTheDeviceUsable) {
  VulkanContext context(testing::testOptions().context);
  const auto start = std::chrono::steady_clock::now();
  const std::uint32_t submissions = warmUpClocks(context, std::chrono::milliseconds(40), {});
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(elapsed, std::chrono::milliseconds(40));
  EXPECT_GE(submissions, 1u);
  // A second warm-up on the same device: the first left no work or state behind.
  EXPECT_GE(warmUpClocks(context, std::chrono::milliseconds(0), {}), 1u);
  EXPECT_TRUE(context.validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
