#include "runtime/materials/material_baker.h"

#include <algorithm>
#include <cmath>
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
// bake.comp's BakeSums layout (MG_BAKE_TIMING): one float a pixel.
constexpr std::uint32_t kTimedBytesPerPixel = 4;

// Which values buffer a BakeProgram writes: the bake's outputs, or the timing's one sum a
// pixel.
enum class BakeStores { Outputs, TimingSum };

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

namespace {

// The bytes of the values buffer of a bake of `settings`' size, refused (std::invalid_argument)
// when the device cannot hold them.
std::uint64_t bakeValueBytes(const VulkanContext& context, const BakeSettings& settings,
                             BakeStores stores) {
  if (settings.width == 0 || settings.height == 0)
    throw std::invalid_argument("the bake size must be at least 1x1");
  const std::uint64_t bytesPerPixel =
      stores == BakeStores::Outputs ? kBakeVec4PerPixel * 16 : kTimedBytesPerPixel;
  const std::uint64_t valueBytes = std::uint64_t(settings.width) * settings.height * bytesPerPixel;
  checkBufferSize(context, valueBytes,
                  "a " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                      " bake (" + std::to_string(bytesPerPixel) + " bytes a pixel)",
                  true);
  return valueBytes;
}

}  // namespace

// One material's bake shader, ready to dispatch into a values buffer: its textures, pipeline
// and descriptor set. Baking and timing record the same dispatch and evaluation, so that a
// timing measures what a bake runs; a timing stores one sum a pixel instead of the outputs.
class MaterialBaker::BakeProgram {
 public:
  BakeProgram(const VulkanContext& context, const std::filesystem::path& shaderCacheDirectory,
              const BakeMaterial& material, VkBuffer values, BakeStores stores)
      : textures_(context, material.textures) {
    VkDevice device = context.device();
    // The shader: the embedded sources plus this material's include, entered through a
    // define so one bake.comp serves every material (and the SPIR-V cache keys on both).
    std::map<std::string, std::string> files = embeddedShaderFiles();
    files["bake_material.glsl"] = material.glsl;
    ShaderCompiler compiler(std::move(files), shaderCacheDirectory);
    std::vector<std::string> defines = {"MG_TEXTURE_COUNT=" + std::to_string(textures_.count()),
                                        "MG_BAKE_EVALUATE=EvaluateMaterial_" + material.name};
    if (stores == BakeStores::TimingSum)
      defines.push_back("MG_BAKE_TIMING");
    const std::vector<std::uint32_t> spirv =
        compiler.compile({"bake.comp", ShaderStage::Compute, std::move(defines)});

    VulkanHandle<VkShaderModule> module = createShaderModule(device, spirv);

    VkDescriptorSetLayoutBinding bindings[2] = {};
    bindings[0].binding = 0;
    bindings[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[0].descriptorCount = 1;
    bindings[0].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    bindings[1].binding = gpu::kBindingTextures;
    bindings[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    bindings[1].descriptorCount = textures_.count();
    bindings[1].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    VkDescriptorSetLayoutCreateInfo setLayoutInfo{
        VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setLayoutInfo.bindingCount = 2;
    setLayoutInfo.pBindings = bindings;
    VkDescriptorSetLayout rawSetLayout = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorSetLayout(device, &setLayoutInfo, nullptr, &rawSetLayout),
            "vkCreateDescriptorSetLayout");
    setLayout_ = VulkanHandle<VkDescriptorSetLayout>(
        rawSetLayout,
        [device](VkDescriptorSetLayout l) { vkDestroyDescriptorSetLayout(device, l, nullptr); });

    VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(BakePush)};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &rawSetLayout;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &pushRange;
    VkPipelineLayout rawLayout = VK_NULL_HANDLE;
    checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &rawLayout),
            "vkCreatePipelineLayout");
    layout_ = VulkanHandle<VkPipelineLayout>(
        rawLayout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });

    pipeline_ = createComputePipeline(context, module.get(), rawLayout, "bake");
    context.pipelineCache().save();

    VkDescriptorPoolSize poolSizes[2] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textures_.count()}};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 2;
    poolInfo.pPoolSizes = poolSizes;
    VkDescriptorPool rawPool = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &rawPool), "vkCreateDescriptorPool");
    pool_ = VulkanHandle<VkDescriptorPool>(
        rawPool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });
    VkDescriptorSetAllocateInfo allocateInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocateInfo.descriptorPool = rawPool;
    allocateInfo.descriptorSetCount = 1;
    allocateInfo.pSetLayouts = &rawSetLayout;
    checkVk(vkAllocateDescriptorSets(device, &allocateInfo, &set_), "vkAllocateDescriptorSets");

    VkDescriptorBufferInfo bufferInfo{values, 0, VK_WHOLE_SIZE};
    std::vector<VkDescriptorImageInfo> imageInfos;
    for (std::uint32_t i = 0; i < textures_.count(); ++i)
      imageInfos.push_back(
          {textures_.sampler(), textures_.view(i), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                      {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    writes[0].dstSet = set_;
    writes[0].dstBinding = 0;
    writes[0].descriptorCount = 1;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[0].pBufferInfo = &bufferInfo;
    writes[1].dstSet = set_;
    writes[1].dstBinding = gpu::kBindingTextures;
    writes[1].descriptorCount = textures_.count();
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[1].pImageInfo = imageInfos.data();
    vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);
  }

  // Records the evaluation of every pixel of `settings`' size into the values buffer.
  void recordDispatch(VkCommandBuffer commands, const BakeSettings& settings) const {
    BakePush push{};
    for (int k = 0; k < 3; ++k) {
      push.boundsMin[k] = settings.boundsMin[k];
      push.boundsMax[k] = settings.boundsMax[k];
      push.normal[k] = settings.normal[k];
    }
    push.size[0] = settings.width;
    push.size[1] = settings.height;
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0,
                            nullptr);
    vkCmdPushConstants(commands, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                       &push);
    vkCmdDispatch(commands, (settings.width + kBakeWorkgroup - 1) / kBakeWorkgroup,
                  (settings.height + kBakeWorkgroup - 1) / kBakeWorkgroup, 1);
  }

 private:
  GpuTextures textures_;
  VulkanHandle<VkDescriptorSetLayout> setLayout_;
  VulkanHandle<VkPipelineLayout> layout_;
  VulkanHandle<VkPipeline> pipeline_;
  VulkanHandle<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with pool_
};

BakeOutputs MaterialBaker::bake(const BakeMaterial& material, const BakeSettings& settings) {
  const VulkanContext& context = *context_;
  const std::uint64_t valueBytes = bakeValueBytes(context, settings, BakeStores::Outputs);
  const std::size_t pixels = std::size_t(settings.width) * settings.height;
  GpuBuffer values = hostBuffer(context, valueBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const BakeProgram program(context, shaderCacheDirectory_, material, values.buffer(),
                            BakeStores::Outputs);
  context.submitAndWait([&](VkCommandBuffer commands) {
    program.recordDispatch(commands, settings);
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

namespace memograph::runtime {

namespace {

// About a quarter of a second of untimed work before the timed dispatches.
constexpr double kBakeWarmUpNs = 250e6;
constexpr std::uint32_t kBakeMaxWarmUps = 4096;

// Makes the next dispatch wait for the one before: they write the same buffer.
void recordDispatchAfterWrites(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                       nullptr);
}

}  // namespace

std::uint32_t bakeWarmUpDispatches(double probeNs) {
  if (!(probeNs > 0.0))
    return kBakeMaxWarmUps;
  const double count = std::ceil(kBakeWarmUpNs / probeNs);
  return count >= double(kBakeMaxWarmUps) ? kBakeMaxWarmUps : std::max(1u, std::uint32_t(count));
}

std::vector<double> MaterialBaker::timeDispatches(const BakeMaterial& material,
                                                  const BakeSettings& settings,
                                                  std::uint32_t dispatches) {
  const VulkanContext& context = *context_;
  VkDevice device = context.device();
  if (dispatches == 0)
    throw std::invalid_argument("time at least one dispatch");
  if (!context.info().timestamps)
    throw std::runtime_error("the device's compute queue has no timestamps");
  // Device-local values, never read back: a host-visible buffer would put the bus's write
  // bandwidth into every dispatch's time.
  const std::uint64_t valueBytes = bakeValueBytes(context, settings, BakeStores::TimingSum);
  GpuBuffer values(context, valueBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  const BakeProgram program(context, shaderCacheDirectory_, material, values.buffer(),
                            BakeStores::TimingSum);

  const std::uint32_t queryCount = 2 * dispatches;
  VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
  queryInfo.queryCount = queryCount;
  VkQueryPool rawQueries = VK_NULL_HANDLE;
  checkVk(vkCreateQueryPool(device, &queryInfo, nullptr, &rawQueries), "vkCreateQueryPool");
  VulkanHandle<VkQueryPool> queries(
      rawQueries, [device](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });

  // The GPU lowers its clocks while the host compiles the pipeline, and raises them again
  // only after some milliseconds of work: dispatches timed at once would time the ramp, and
  // one graph's time would differ from call to call by more than the nodes do. So the timed
  // dispatches follow untimed ones that keep the GPU busy for about kBakeWarmUpNs, counted
  // from one probe dispatch's time.
  context.submitAndWait([&](VkCommandBuffer commands) {
    vkCmdResetQueryPool(commands, rawQueries, 0, 2);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, rawQueries, 0);
    program.recordDispatch(commands, settings);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, rawQueries, 1);
  });
  std::uint64_t probe[2] = {};
  checkVk(
      vkGetQueryPoolResults(device, rawQueries, 0, 2, sizeof(probe), probe, sizeof(std::uint64_t),
                            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
      "vkGetQueryPoolResults (bake probe)");
  const std::uint32_t warmUps =
      bakeWarmUpDispatches(double(probe[1] - probe[0]) * context.info().timestampPeriodNs);
  context.submitAndWait([&](VkCommandBuffer commands) {
    for (std::uint32_t w = 0; w < warmUps; ++w) {
      recordDispatchAfterWrites(commands);
      program.recordDispatch(commands, settings);
    }
    vkCmdResetQueryPool(commands, rawQueries, 0, queryCount);
    for (std::uint32_t d = 0; d < dispatches; ++d) {
      // Each dispatch waits for the one before (they write the same buffer), and both
      // timestamps wait for the compute work recorded before them (a top-of-pipe one would
      // not), so that one pair brackets one dispatch alone.
      recordDispatchAfterWrites(commands);
      vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, rawQueries, 2 * d);
      program.recordDispatch(commands, settings);
      vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, rawQueries, 2 * d + 1);
    }
  });
  std::vector<std::uint64_t> ticks(queryCount);
  checkVk(vkGetQueryPoolResults(
              device, rawQueries, 0, queryCount, ticks.size() * sizeof(std::uint64_t), ticks.data(),
              sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults (bake timestamps)");
  std::vector<double> nanoseconds(dispatches);
  for (std::uint32_t d = 0; d < dispatches; ++d)
    nanoseconds[d] = double(ticks[2 * d + 1] - ticks[2 * d]) * context.info().timestampPeriodNs;
  return nanoseconds;
}

}  // namespace memograph::runtime
