#include "runtime/vk/compute_pipeline.h"

#include <string>

#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"
#include "runtime/vk/vulkan_error.h"

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

VulkanHandle<VkPipelineLayout> createPipelineLayout(VkDevice device, VkDescriptorSetLayout set,
                                                    VkShaderStageFlags pushStages,
                                                    std::uint32_t pushBytes) {
  const VkPushConstantRange push{pushStages, 0, pushBytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = set != VK_NULL_HANDLE ? 1 : 0;
  info.pSetLayouts = &set;
  info.pushConstantRangeCount = pushStages != 0 ? 1 : 0;
  info.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
  return VulkanHandle<VkPipelineLayout>(
      layout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });
}

PipelineCreationFeedback::PipelineCreationFeedback(const VulkanContext& context,
                                                   std::uint32_t stageCount)
    : context_(context), stages_(stageCount) {
  info_.sType = VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO;
  info_.pPipelineCreationFeedback = &pipeline_;
  info_.pipelineStageCreationFeedbackCount = stageCount;
  info_.pPipelineStageCreationFeedbacks = stages_.data();
}

const void* PipelineCreationFeedback::chain(const void* next) {
  if (!context_.info().pipelineCreationFeedback)
    return next;
  info_.pNext = next;
  return &info_;
}

void PipelineCreationFeedback::count() const {
  context_.pipelineCache().countCreated(pipeline_, std::chrono::steady_clock::now() - start_);
}

VulkanHandle<VkPipeline> createComputePipeline(const VulkanContext& context, VkShaderModule module,
                                               VkPipelineLayout layout, const char* what) {
  return createComputePipeline(context, module, layout, what, context.pipelineCache().handle());
}

VulkanHandle<VkPipeline> createComputePipeline(const VulkanContext& context, VkShaderModule module,
                                               VkPipelineLayout layout, const char* what,
                                               VkPipelineCache cache) {
  VkDevice device = context.device();
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.layout = layout;
  PipelineCreationFeedback feedback(context, 1);
  info.pNext = feedback.chain(info.pNext);
  PipelineStatistics* statistics = context.pipelineStatistics();
  if (statistics)
    info.flags |= PipelineStatistics::captureFlags();
  VkPipeline pipeline = VK_NULL_HANDLE;
  checkVk(vkCreateComputePipelines(device, cache, 1, &info, nullptr, &pipeline),
          ("vkCreateComputePipelines (" + std::string(what) + ")").c_str());
  feedback.count();
  VulkanHandle<VkPipeline> owned(pipeline,
                                 [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });
  if (statistics)
    statistics->record(pipeline, what);
  return owned;
}

PushConstantPass createPushConstantPass(const VulkanContext& context, const std::string& file,
                                        std::uint32_t pushBytes,
                                        const std::filesystem::path& shaderCacheDirectory,
                                        const char* what) {
  VkDevice device = context.device();
  ShaderCompiler compiler(embeddedShaderFiles(), shaderCacheDirectory);
  auto module = createShaderModule(device, compiler.compile({file, ShaderStage::Compute, {}}));
  PushConstantPass pass;
  pass.layout =
      createPipelineLayout(device, VK_NULL_HANDLE, VK_SHADER_STAGE_COMPUTE_BIT, pushBytes);
  pass.pipeline = createComputePipeline(context, module.get(), pass.layout.get(), what);
  return pass;
}

}  // namespace memograph::runtime
