#include "runtime/trace_pipelines.h"

#include <array>
#include <cstring>
#include <string>
#include <vector>

#include "runtime/shaders/shared_types.h"
#include "runtime/vulkan_error.h"

namespace memograph::runtime {

namespace {

VulkanHandle<VkShaderModule> createModule(VkDevice device,
                                          const std::vector<std::uint32_t>& spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size() * sizeof(std::uint32_t);
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  checkVk(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
  return VulkanHandle<VkShaderModule>(
      module, [device](VkShaderModule m) { vkDestroyShaderModule(device, m, nullptr); });
}

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

}  // namespace

TracePipeline::TracePipeline(const VulkanContext& context, ShaderCompiler& compiler,
                             std::uint32_t textureCount)
    : context_(context), backend_(context.backend()) {
  VkDevice device = context.device();
  bool query = backend_ == Backend::RayQuery;
  VkShaderStageFlags stages = query ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_RAYGEN_BIT_KHR;

  using gpu::uint;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  auto add = [&](uint binding, VkDescriptorType type, uint count = 1) {
    bindings.push_back({binding, type, count, stages, nullptr});
  };
  add(gpu::kBindingTlas, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR);
  add(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  add(gpu::kBindingAccumulation, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingVertices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingMeshes, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingEnvironment, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingTextures, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textureCount);
  add(gpu::kBindingRayCounter, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout),
          "vkCreateDescriptorSetLayout");
  setLayout_ = VulkanHandle<VkDescriptorSetLayout>(setLayout, [device](VkDescriptorSetLayout l) {
    vkDestroyDescriptorSetLayout(device, l, nullptr);
  });

  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
  layout_ = VulkanHandle<VkPipelineLayout>(
      layout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });

  std::vector<std::string> defines = {"MG_TEXTURE_COUNT=" + std::to_string(textureCount),
                                      query ? "MG_BACKEND_QUERY=1" : "MG_BACKEND_PIPELINE=1"};
  if (context.info().subgroupArithmeticStages & stages)
    defines.push_back("MG_SUBGROUP_RAY_COUNT=1");
  auto destroyPipeline = [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); };

  if (query) {
    auto module =
        createModule(device, compiler.compile({"path_tracer.glsl", ShaderStage::Compute, defines}));
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.get();
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    checkVk(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
            "vkCreateComputePipelines");
    pipeline_ = VulkanHandle<VkPipeline>(pipeline, destroyPipeline);
    return;
  }

  // Ray-tracing pipeline: raygen (the path tracer), two misses, one triangle hit group.
  std::array<VulkanHandle<VkShaderModule>, 4> modules = {
      createModule(device, compiler.compile({"path_tracer.glsl", ShaderStage::RayGen, defines})),
      createModule(device, compiler.compile({"trace_miss.rmiss", ShaderStage::Miss, {}})),
      createModule(device, compiler.compile({"trace_shadow.rmiss", ShaderStage::Miss, {}})),
      createModule(device, compiler.compile({"trace_hit.rchit", ShaderStage::ClosestHit, {}}))};
  const VkShaderStageFlagBits stageBits[4] = {
      VK_SHADER_STAGE_RAYGEN_BIT_KHR, VK_SHADER_STAGE_MISS_BIT_KHR, VK_SHADER_STAGE_MISS_BIT_KHR,
      VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR};
  std::array<VkPipelineShaderStageCreateInfo, 4> shaderStages{};
  std::array<VkRayTracingShaderGroupCreateInfoKHR, 4> groups{};
  for (std::uint32_t i = 0; i < 4; ++i) {
    shaderStages[i] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    shaderStages[i].stage = stageBits[i];
    shaderStages[i].module = modules[i].get();
    shaderStages[i].pName = "main";
    groups[i] = {VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    groups[i].generalShader = VK_SHADER_UNUSED_KHR;
    groups[i].closestHitShader = VK_SHADER_UNUSED_KHR;
    groups[i].anyHitShader = VK_SHADER_UNUSED_KHR;
    groups[i].intersectionShader = VK_SHADER_UNUSED_KHR;
    if (i < 3) {
      groups[i].type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
      groups[i].generalShader = i;
    } else {
      groups[i].type = VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
      groups[i].closestHitShader = i;
    }
  }
  VkRayTracingPipelineCreateInfoKHR info{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  info.stageCount = 4;
  info.pStages = shaderStages.data();
  info.groupCount = 4;
  info.pGroups = groups.data();
  info.maxPipelineRayRecursionDepth = 1;  // raygen traces; hit shaders never do
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  checkVk(context.functions().createRayTracingPipelines(device, VK_NULL_HANDLE, VK_NULL_HANDLE, 1,
                                                        &info, nullptr, &pipeline),
          "vkCreateRayTracingPipelinesKHR");
  pipeline_ = VulkanHandle<VkPipeline>(pipeline, destroyPipeline);

  // Shader-binding table: [raygen][miss, shadow miss][hit], each region base-aligned.
  const auto& rt = context.info().rayTracingProperties;
  std::uint32_t handleSize = rt.shaderGroupHandleSize;
  VkDeviceSize stride = alignUp(handleSize, rt.shaderGroupHandleAlignment);
  VkDeviceSize base = rt.shaderGroupBaseAlignment;
  std::vector<std::uint8_t> handles(std::size_t(handleSize) * 4);
  checkVk(context.functions().getRayTracingShaderGroupHandles(device, pipeline, 0, 4,
                                                              handles.size(), handles.data()),
          "vkGetRayTracingShaderGroupHandlesKHR");
  VkDeviceSize raygenOffset = 0;
  VkDeviceSize missOffset = alignUp(stride, base);
  VkDeviceSize hitOffset = alignUp(missOffset + 2 * stride, base);
  VkDeviceSize tableSize = hitOffset + stride;
  std::vector<std::uint8_t> table(tableSize, 0);
  std::memcpy(&table[raygenOffset], &handles[0], handleSize);
  std::memcpy(&table[missOffset], &handles[handleSize], handleSize);
  std::memcpy(&table[missOffset + stride], &handles[2 * handleSize], handleSize);
  std::memcpy(&table[hitOffset], &handles[3 * handleSize], handleSize);
  shaderBindingTable_ = GpuBuffer(
      context, tableSize + base,
      VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceAddress tableAddress = alignUp(shaderBindingTable_.address(), base);
  shaderBindingTable_.write(table.data(), table.size(),
                            tableAddress - shaderBindingTable_.address());
  raygenRegion_ = {tableAddress + raygenOffset, alignUp(stride, base), alignUp(stride, base)};
  missRegion_ = {tableAddress + missOffset, stride, 2 * stride};
  hitRegion_ = {tableAddress + hitOffset, stride, stride};
}

void TracePipeline::record(VkCommandBuffer commands, VkDescriptorSet set, std::uint32_t width,
                           std::uint32_t height) const {
  if (backend_ == Backend::RayQuery) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(commands, (width + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize,
                  (height + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize, 1);
    return;
  }
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_.get());
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, layout_.get(), 0, 1,
                          &set, 0, nullptr);
  context_.functions().cmdTraceRays(commands, &raygenRegion_, &missRegion_, &hitRegion_,
                                    &callableRegion_, width, height, 1);
}

}  // namespace memograph::runtime
