// Shader modules from SPIR-V and compute pipelines from a module: the path tracer's query
// backend (trace_pipelines), the bake (material_baker) and the cache self-test use them.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vulkan_handle.h"

namespace memograph::runtime {

// Throws std::runtime_error on a Vulkan error.
VulkanHandle<VkShaderModule> createShaderModule(VkDevice device,
                                                const std::vector<std::uint32_t>& spirv);

// A pipeline layout of at most one descriptor set layout (VK_NULL_HANDLE: none) and at most
// one push-constant range (`pushStages` 0: none). Throws std::runtime_error.
VulkanHandle<VkPipelineLayout> createPipelineLayout(VkDevice device, VkDescriptorSetLayout set,
                                                    VkShaderStageFlags pushStages = 0,
                                                    std::uint32_t pushBytes = 0);

// A compute pipeline of `module`'s "main" under `layout`; `what` names it in errors.
VulkanHandle<VkPipeline> createComputePipeline(VkDevice device, VkShaderModule module,
                                               VkPipelineLayout layout, const char* what);

}  // namespace memograph::runtime
