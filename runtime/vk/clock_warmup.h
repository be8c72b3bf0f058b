// Keeps a GPU busy for a while before frames are timed. A discrete GPU lowers its clocks
// while it idles (through the scene's build and pipeline creation, all host work) and raises
// them only once it has been under load for a while, so the first frames after such a spell
// ran slower than the rest ([results](docs/results.md), the city in both architectures).
// `memograph bench` warms the clocks so that its frames time the frames, not the clocks.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>

#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

class ClockWarmup {
 public:
  // The compute pass that only spins (shaders/common/clock_warmup.comp), its SPIR-V cached in
  // `shaderCacheDirectory` (none when empty). Throws VulkanError on a device failure.
  ClockWarmup(const VulkanContext& context, const std::filesystem::path& shaderCacheDirectory);

  // Submits the pass, one submission after another, each grown until it takes about 5 ms,
  // until `duration` of wall time has passed; returns the submissions made (at least one).
  std::uint32_t run(std::chrono::milliseconds duration);

 private:
  const VulkanContext& context_;
  PushConstantPass pass_;
  GpuBuffer sink_;
  std::uint32_t iterations_ = 16;  // a submission's loop count, grown as run() measures
};

}  // namespace memograph::runtime
