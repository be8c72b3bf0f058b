// Shader modules from SPIR-V and compute pipelines from a module: the path tracer's query
// backend (trace_pipelines), the bake (material_baker) and the cache self-test use them;
// and the small passes whose only input is their push constants (the GPU instance fill, the
// vertex pass).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// Throws std::runtime_error on a Vulkan error.
VulkanHandle<VkShaderModule> createShaderModule(VkDevice device,
                                                const std::vector<std::uint32_t>& spirv);

// A pipeline layout of at most one descriptor set layout (VK_NULL_HANDLE: none) and at most
// one push-constant range (`pushStages` 0: none). Throws std::runtime_error.
VulkanHandle<VkPipelineLayout> createPipelineLayout(VkDevice device, VkDescriptorSetLayout set,
                                                    VkShaderStageFlags pushStages = 0,
                                                    std::uint32_t pushBytes = 0);

// What the driver says of one pipeline it creates (VK_EXT_pipeline_creation_feedback),
// where the device has it: chain() puts the request into a create info's pNext chain, and
// count() gives the answer to the context's pipeline cache, after the pipeline is created,
// with the time since this object was made (just before the creation call): summed over the
// pipelines created on several threads, against the wall time, it says whether creating
// them in parallel paid.
class PipelineCreationFeedback {
 public:
  PipelineCreationFeedback(const VulkanContext& context, std::uint32_t stageCount);
  PipelineCreationFeedback(const PipelineCreationFeedback&) = delete;
  PipelineCreationFeedback& operator=(const PipelineCreationFeedback&) = delete;
  // `next` where the device has no feedback; else this request, followed by `next`.
  const void* chain(const void* next);
  void count() const;

 private:
  const VulkanContext& context_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  VkPipelineCreationFeedback pipeline_{};
  std::vector<VkPipelineCreationFeedback> stages_;
  VkPipelineCreationFeedbackCreateInfo info_{};
};

// A compute pipeline of `module`'s "main" under `layout`, created with the context's
// pipeline cache; `what` names it in errors.
VulkanHandle<VkPipeline> createComputePipeline(const VulkanContext& context, VkShaderModule module,
                                               VkPipelineLayout layout, const char* what);
// The same with `cache` instead of the context's (a thread's own, ThreadPipelineCaches).
VulkanHandle<VkPipeline> createComputePipeline(const VulkanContext& context, VkShaderModule module,
                                               VkPipelineLayout layout, const char* what,
                                               VkPipelineCache cache);

// A compute pass that reads and writes only through buffer device addresses in its push
// constants (`pushBytes` of them), so it needs no descriptor set: the embedded shader `file`
// compiled (its SPIR-V cached in `shaderCacheDirectory`, none when empty), its layout and its
// pipeline; `what` names it in errors.
struct PushConstantPass {
  VulkanHandle<VkPipelineLayout> layout;
  VulkanHandle<VkPipeline> pipeline;
};
PushConstantPass createPushConstantPass(const VulkanContext& context, const std::string& file,
                                        std::uint32_t pushBytes,
                                        const std::filesystem::path& shaderCacheDirectory,
                                        const char* what);

}  // namespace memograph::runtime
