#include "runtime/materials/material_baker.h"

#include <map>
#include <stdexcept>
#include <utility>

#include "runtime/scene/gpu_textures.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"
#include "runtime/vk/vulkan_error.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

namespace {

// Mirrors bake.comp's BakePush.
struct BakePush {
  float boundsMin[4];
  float boundsMax[4];
  float normal[4];
  std::uint32_t size[4];
};
static_assert(sizeof(BakePush) == 64);

constexpr std::uint32_t kBakeWorkgroup = 8;     // bake.comp's local size
constexpr std::uint32_t kBakeVec4PerPixel = 4;  // bake.comp's BakeValues layout

}  // namespace

namespace {

// The device's pipeline cache beside the SPIR-V cache, as the renderer keeps it.
ContextOptions withPipelineCache(ContextOptions options,
                                 const std::filesystem::path& shaderCacheDirectory) {
  options.pipelineCacheDirectory = shaderCacheDirectory;
  return options;
}

}  // namespace

MaterialBaker::MaterialBaker(const ContextOptions& options,
                             std::filesystem::path shaderCacheDirectory)
    : context_(std::make_unique<VulkanContext>(withPipelineCache(options, shaderCacheDirectory))),
      shaderCacheDirectory_(std::move(shaderCacheDirectory)) {}

MaterialBaker::~MaterialBaker() = default;

BakeOutputs MaterialBaker::bake(const BakeMaterial& material, const BakeSettings& settings) {
  const VulkanContext& context = *context_;
  VkDevice device = context.device();
  if (settings.width == 0 || settings.height == 0)
    throw std::invalid_argument("the bake size must be at least 1x1");
  const std::size_t pixels = std::size_t(settings.width) * settings.height;
  const std::uint64_t valueBytes = std::uint64_t(pixels) * kBakeVec4PerPixel * 16;
  checkBufferSize(context, valueBytes,
                  "a " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                      " bake (64 bytes a pixel)",
                  true);

  // The shader: the embedded sources plus this material's include, entered through a
  // define so one bake.comp serves every material (and the SPIR-V cache keys on both).
  std::map<std::string, std::string> files = embeddedShaderFiles();
  files["bake_material.glsl"] = material.glsl;
  GpuTextures textures(context, material.textures);
  ShaderCompiler compiler(std::move(files), shaderCacheDirectory_);
  const std::vector<std::uint32_t> spirv =
      compiler.compile({"bake.comp",
                        ShaderStage::Compute,
                        {"MG_TEXTURE_COUNT=" + std::to_string(textures.count()),
                         "MG_BAKE_EVALUATE=EvaluateMaterial_" + material.name}});

  VulkanHandle<VkShaderModule> module = createShaderModule(device, spirv);

  VkDescriptorSetLayoutBinding bindings[2] = {};
  bindings[0].binding = 0;
  bindings[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  bindings[0].descriptorCount = 1;
  bindings[0].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  bindings[1].binding = gpu::kBindingTextures;
  bindings[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  bindings[1].descriptorCount = textures.count();
  bindings[1].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  VkDescriptorSetLayoutCreateInfo setLayoutInfo{
      VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setLayoutInfo.bindingCount = 2;
  setLayoutInfo.pBindings = bindings;
  VkDescriptorSetLayout rawSetLayout = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorSetLayout(device, &setLayoutInfo, nullptr, &rawSetLayout),
          "vkCreateDescriptorSetLayout");
  VulkanHandle<VkDescriptorSetLayout> setLayout(rawSetLayout, [device](VkDescriptorSetLayout l) {
    vkDestroyDescriptorSetLayout(device, l, nullptr);
  });

  VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(BakePush)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &rawSetLayout;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &pushRange;
  VkPipelineLayout rawLayout = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &rawLayout),
          "vkCreatePipelineLayout");
  VulkanHandle<VkPipelineLayout> layout(
      rawLayout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });

  VulkanHandle<VkPipeline> pipeline =
      createComputePipeline(context, module.get(), rawLayout, "bake");
  context.pipelineCache().save();

  VkDescriptorPoolSize poolSizes[2] = {
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textures.count()}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = poolSizes;
  VkDescriptorPool rawPool = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &rawPool), "vkCreateDescriptorPool");
  VulkanHandle<VkDescriptorPool> pool(
      rawPool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });
  VkDescriptorSetAllocateInfo allocateInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocateInfo.descriptorPool = rawPool;
  allocateInfo.descriptorSetCount = 1;
  allocateInfo.pSetLayouts = &rawSetLayout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  checkVk(vkAllocateDescriptorSets(device, &allocateInfo, &set), "vkAllocateDescriptorSets");

  GpuBuffer values = hostBuffer(context, valueBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  VkDescriptorBufferInfo bufferInfo{values.buffer(), 0, VK_WHOLE_SIZE};
  std::vector<VkDescriptorImageInfo> imageInfos;
  for (std::uint32_t i = 0; i < textures.count(); ++i)
    imageInfos.push_back(
        {textures.sampler(), textures.view(i), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                    {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  writes[0].dstSet = set;
  writes[0].dstBinding = 0;
  writes[0].descriptorCount = 1;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[0].pBufferInfo = &bufferInfo;
  writes[1].dstSet = set;
  writes[1].dstBinding = gpu::kBindingTextures;
  writes[1].descriptorCount = textures.count();
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[1].pImageInfo = imageInfos.data();
  vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);

  BakePush push{};
  for (int k = 0; k < 3; ++k) {
    push.boundsMin[k] = settings.boundsMin[k];
    push.boundsMax[k] = settings.boundsMax[k];
    push.normal[k] = settings.normal[k];
  }
  push.size[0] = settings.width;
  push.size[1] = settings.height;
  context.submitAndWait([&](VkCommandBuffer commands) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, rawLayout, 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(commands, rawLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(commands, (settings.width + kBakeWorkgroup - 1) / kBakeWorkgroup,
                  (settings.height + kBakeWorkgroup - 1) / kBakeWorkgroup, 1);
    // The host reads the values after the wait: make the shader's writes visible to it.
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
  });

  std::vector<float> raw(pixels * kBakeVec4PerPixel * 4);
  values.read(raw.data(), raw.size() * sizeof(float));
  BakeOutputs out;
  out.width = settings.width;
  out.height = settings.height;
  out.baseColor.resize(pixels);
  out.metallic.resize(pixels);
  out.roughness.resize(pixels);
  out.specular.resize(pixels);
  out.specularTint.resize(pixels);
  out.cyclesPrincipled.resize(pixels);
  out.normal.resize(pixels);
  out.emission.resize(pixels);
  out.opacity.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    const float* v = &raw[p * kBakeVec4PerPixel * 4];
    out.baseColor[p] = {v[0], v[1], v[2]};
    out.metallic[p] = v[3];
    out.normal[p] = {v[4], v[5], v[6]};
    out.roughness[p] = v[7];
    out.emission[p] = {v[8], v[9], v[10]};
    out.opacity[p] = v[11];
    out.specular[p] = v[12];
    out.specularTint[p] = v[13];
    out.cyclesPrincipled[p] = v[14];
  }
  return out;
}

}  // namespace memograph::runtime
