#include "runtime/vk/clock_warmup.h"

#include <algorithm>

namespace memograph::runtime {

namespace {

struct WarmupPush {
  glm::uvec2 sink;
  std::uint32_t iterations;
};

// 1024 work groups of 256: 262,144 invocations, about what an H100's 132 multiprocessors
// hold at once (2,048 each), so that every multiprocessor is busy.
constexpr std::uint32_t kWorkgroups = 1024;
// A submission is grown (its iterations doubled) until it takes this long, so that the
// host's turnaround between submissions leaves the GPU idle for a small share of the time.
constexpr auto kSubmission = std::chrono::milliseconds(5);
constexpr std::uint32_t kMaxIterations = 1u << 24;

}  // namespace

ClockWarmup::ClockWarmup(const VulkanContext& context,
                         const std::filesystem::path& shaderCacheDirectory)
    : context_(context),
      pass_(createPushConstantPass(context, "clock_warmup.comp", sizeof(WarmupPush),
                                   shaderCacheDirectory, "clock warm-up")),
      sink_(context, sizeof(std::uint32_t),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
            VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) {}

std::uint32_t ClockWarmup::run(std::chrono::milliseconds duration) {
  const auto start = std::chrono::steady_clock::now();
  std::uint32_t submissions = 0;
  do {
    const WarmupPush push{addressWords(sink_.address()), iterations_};
    const auto submitted = std::chrono::steady_clock::now();
    context_.submitAndWait([&](VkCommandBuffer commands) {
      vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pass_.pipeline.get());
      vkCmdPushConstants(commands, pass_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                         &push);
      vkCmdDispatch(commands, kWorkgroups, 1, 1);
    });
    ++submissions;
    if (std::chrono::steady_clock::now() - submitted < kSubmission)
      iterations_ = std::min(iterations_ * 2, kMaxIterations);
  } while (std::chrono::steady_clock::now() - start < duration);
  return submissions;
}

}  // namespace memograph::runtime
