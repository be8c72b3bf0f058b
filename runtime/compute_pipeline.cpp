#include "runtime/compute_pipeline.h"

#include <string>

#include "runtime/vulkan_error.h"

namespace memograph::runtime {

VulkanHandle<VkShaderModule> createShaderModule(VkDevice device,
                                                const std::vector<std::uint32_t>& spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size() * sizeof(std::uint32_t);
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  checkVk(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
  return VulkanHandle<VkShaderModule>(
      module, [device](VkShaderModule m) { vkDestroyShaderModule(device, m, nullptr); });
}

VulkanHandle<VkPipeline> createComputePipeline(VkDevice device, VkShaderModule module,
                                               VkPipelineLayout layout, const char* what) {
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  checkVk(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
          ("vkCreateComputePipelines (" + std::string(what) + ")").c_str());
  return VulkanHandle<VkPipeline>(
      pipeline, [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });
}

}  // namespace memograph::runtime
