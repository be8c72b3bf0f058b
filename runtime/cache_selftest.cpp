#include "runtime/cache_selftest.h"

#include <map>
#include <stdexcept>

#include "runtime/gpu_buffer.h"
#include "runtime/shader_compiler.h"
#include "runtime/shader_sources.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/vulkan_error.h"
#include "runtime/vulkan_handle.h"

namespace memograph::runtime {
namespace {

constexpr std::uint32_t kStressValues = 12;

// Stubs for what texel_cache.glsl expects from the path tracer and the material prelude;
// the programs call the entry protocol directly with their own keys.
constexpr const char* kProgramHead = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#ifdef MG_CACHE_CLOCK_COUNTER
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#endif
#include "shared_types.h"
layout(set = 0, binding = kBindingFrame, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = kBindingRayCounter, std430) buffer ResultBlock {
  Counters counters;  // texel_cache.glsl counts occupancy and keeps its counter clock here
  uint results[];
};
struct float2_D { vec2 v; vec2 x; vec2 y; };
struct MaterialInputs { float2_D uv; };
struct MaterialOutputs {
  vec3 baseColor; float metallic; float roughness; vec3 normal; vec3 emission; float opacity;
  float specular; float specularTint; float cyclesPrincipled;
};
MaterialOutputs mg_defaultMaterialOutputs(MaterialInputs inputs) {
  MaterialOutputs o;
  o.baseColor = vec3(0.0); o.metallic = 0.0; o.roughness = 0.0; o.normal = vec3(0.0);
  o.emission = vec3(0.0); o.opacity = 1.0; o.specular = 0.5; o.specularTint = 0.0;
  o.cyclesPrincipled = 0.0;
  return o;
}
const uvec4 mg_materialCacheInfo[1] = uvec4[](uvec4(0u));
void evaluateMaterialDirect(uint id, MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
}
#include "texel_cache.glsl"
#ifdef SELFTEST_RAY_CONE
#include "ray_cone.glsl"
#endif
#ifdef STRESS_IMAGE
// The values of entry e in texels (3e .. 3e + 2, 0) of an rgba32f image, read and written
// under the same entry protocol as the tile cache's image storage.
layout(set = 0, binding = kBindingTileImage, rgba32f) coherent uniform image2D tileImage;
void stressStore(uint entry, float values[MG_CACHE_VALUES]) {
  for (uint g = 0u; g < 3u; ++g)
    imageStore(tileImage, ivec2(3u * entry + g, 0),
               vec4(values[4u * g], values[4u * g + 1u], values[4u * g + 2u], values[4u * g + 3u]));
}
bool stressRead(CacheKey key, out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  int entry = cacheFind(key);
  if (entry < 0) return false;
  uint counterBefore = cacheReadBegin(uint(entry), key);
  for (uint g = 0u; g < 3u; ++g) {
    vec4 v = imageLoad(tileImage, ivec2(3u * uint(entry) + g, 0));
    for (uint c = 0u; c < 4u; ++c) values[4u * g + c] = v[c];
  }
  return cacheReadValid(uint(entry), key, counterBefore);
}
void stressWrite(CacheKey key, float values[MG_CACHE_VALUES]) {
  int entry = cacheLock(key);
  if (entry < 0) return;
  stressStore(uint(entry), values);
  cacheUnlock(uint(entry), key);
}
#else
bool stressRead(CacheKey key, out float values[MG_CACHE_VALUES]) { return cacheRead(key, values); }
void stressWrite(CacheKey key, float values[MG_CACHE_VALUES]) { cacheWrite(key, values); }
#endif
layout(local_size_x = 64) in;
void main() {
)";

// results[0..3]: hits, torn, writes, misses.
constexpr const char* kStressBody = R"(
  uint id = gl_GlobalInvocationID.x;
  uint localHits = 0u, localTorn = 0u, localWrites = 0u, localMisses = 0u;
  for (uint it = 0u; it < uint(STRESS_ITERATIONS); ++it) {
    uint k = cachePcg(id * 7919u + it * 104729u) % 64u;
    CacheKey key;
    key.hash = k + 1u;
    key.base = cachePcg(k ^ 0x5bd1e995u) % (frame.cache.x - uint(MG_CACHE_PROBE));
    float values[MG_CACHE_VALUES];
#ifdef STRESS_UNPROTECTED
    uint offset = cacheEntryOffset(key.base);
    bool hit = cacheData[offset] == key.hash;
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i)
      values[i] = uintBitsToFloat(cacheData[offset + kCacheHeader + i]);
    if (!hit) {
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) {
        values[i] = float(k * 16u + i);
        cacheData[offset + kCacheHeader + i] = floatBitsToUint(values[i]);
      }
      cacheData[offset] = key.hash;
    }
    if (hit) {
#else
    if (stressRead(key, values)) {
#endif
      localHits += 1u;
      bool ok = true;
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i)
        ok = ok && values[i] == float(k * 16u + i);
      if (!ok) localTorn += 1u;
    } else {
      localMisses += 1u;
#ifndef STRESS_UNPROTECTED
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = float(k * 16u + i);
      stressWrite(key, values);
#endif
      localWrites += 1u;
    }
  }
  atomicAdd(results[0], localHits);
  atomicAdd(results[1], localTorn);
  atomicAdd(results[2], localWrites);
  atomicAdd(results[3], localMisses);
)";

template <typename T>
VulkanHandle<T> handle(VkDevice device, T raw,
                       void (*destroy)(VkDevice, T, const VkAllocationCallbacks*)) {
  return VulkanHandle<T>(raw, [device, destroy](T object) { destroy(device, object, nullptr); });
}

struct Program {
  std::string body;
  std::vector<std::string> defines;
  std::uint32_t entries = kCacheStressEntries;
  std::uint32_t invocations = 64;
  std::uint64_t clockStart = 0;
  std::uint32_t resultWords = 4;
  bool image = false;
};

// Compiles and runs one program; returns gpu::Counters then the result words.
std::pair<gpu::Counters, std::vector<std::uint32_t>> runProgram(const VulkanContext& context,
                                                                const Program& program) {
  if (program.invocations == 0 || program.invocations % 64 != 0)
    throw std::invalid_argument("cache self-test: invocations must be a positive multiple of 64");
  VkDevice device = context.device();
  std::map<std::string, std::string> files;
  for (const auto& shader : embeddedShaders())
    files[std::string(shader.name)] = std::string(shader.text);
  files["cache_selftest.comp"] = std::string(kProgramHead) + program.body + "\n}\n";
  ShaderCompiler compiler(std::move(files), {});
  std::vector<std::uint32_t> spirv =
      compiler.compile({"cache_selftest.comp", ShaderStage::Compute, program.defines});
  std::uint32_t values = 1, header = gpu::kCacheEntryHeader, entryWords = 0;
  bool entryWordsGiven = false;
  for (const std::string& d : program.defines) {
    if (d.rfind("MG_CACHE_VALUES=", 0) == 0)
      values = std::uint32_t(std::stoul(d.substr(16)));
    if (d == "MG_CACHE_UPDATE_COUNTER=1")
      header = gpu::kCacheEntryHeaderWithCounter;
    if (d.rfind("MG_CACHE_ENTRY_WORDS=", 0) == 0) {
      entryWords = std::uint32_t(std::stoul(d.substr(21)));
      entryWordsGiven = true;
    }
  }
  if (!entryWordsGiven)
    entryWords = values;  // fp32 values in the entry

  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size() * sizeof(std::uint32_t);
  moduleInfo.pCode = spirv.data();
  VkShaderModule rawModule = VK_NULL_HANDLE;
  checkVk(vkCreateShaderModule(device, &moduleInfo, nullptr, &rawModule), "vkCreateShaderModule");
  auto module = handle(device, rawModule, vkDestroyShaderModule);

  const std::uint32_t bindingCount = program.image ? 4 : 3;
  VkDescriptorSetLayoutBinding bindings[4] = {
      {gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {gpu::kBindingRayCounter, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {gpu::kBindingCache, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {gpu::kBindingTileImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr}};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = bindingCount;
  setInfo.pBindings = bindings;
  VkDescriptorSetLayout rawSetLayout = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &rawSetLayout), "set layout");
  auto setLayout = handle(device, rawSetLayout, vkDestroyDescriptorSetLayout);
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &rawSetLayout;
  VkPipelineLayout rawLayout = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &rawLayout), "pipeline layout");
  auto layout = handle(device, rawLayout, vkDestroyPipelineLayout);
  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = rawModule;
  pipelineInfo.stage.pName = "main";
  pipelineInfo.layout = rawLayout;
  VkPipeline rawPipeline = VK_NULL_HANDLE;
  checkVk(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &rawPipeline),
          "compute pipeline");
  auto pipeline = handle(device, rawPipeline, vkDestroyPipeline);

  gpu::FrameConstants frame{};
  frame.cache = glm::uvec4(program.entries, 1u, 0u, 0u);
  GpuBuffer frameBuffer = hostBuffer(context, sizeof frame, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  frameBuffer.write(&frame, sizeof frame);
  std::vector<std::uint8_t> zero(sizeof(gpu::Counters) + 4 * std::max(program.resultWords, 1u), 0);
  GpuBuffer results = hostBuffer(context, zero.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  results.write(zero.data(), zero.size());
  gpu::Counters start{};
  start.cacheClock = program.clockStart;
  results.write(&start, sizeof start);
  std::vector<std::uint32_t> emptyCache(std::size_t(program.entries) * (header + entryWords), 0u);
  GpuBuffer cache = hostBuffer(context, emptyCache.size() * sizeof(std::uint32_t),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  cache.write(emptyCache.data(), emptyCache.size() * sizeof(std::uint32_t));

  // The image mode's rgba32f storage image: 3 texels (12 values) per entry, one row.
  VulkanHandle<VkImage> image;
  VulkanHandle<VkDeviceMemory> imageMemory;
  VulkanHandle<VkImageView> imageView;
  if (program.image) {
    VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    imageInfo.imageType = VK_IMAGE_TYPE_2D;
    imageInfo.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    imageInfo.extent = {3 * program.entries, 1, 1};
    imageInfo.mipLevels = 1;
    imageInfo.arrayLayers = 1;
    imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
    imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
    imageInfo.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    imageInfo.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage rawImage = VK_NULL_HANDLE;
    checkVk(vkCreateImage(device, &imageInfo, nullptr, &rawImage), "vkCreateImage (self-test)");
    image = handle(device, rawImage, vkDestroyImage);
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, rawImage, &requirements);
    VkMemoryAllocateInfo allocateInfo{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocateInfo.allocationSize = requirements.size;
    allocateInfo.memoryTypeIndex =
        context.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkDeviceMemory rawMemory = VK_NULL_HANDLE;
    checkVk(vkAllocateMemory(device, &allocateInfo, nullptr, &rawMemory), "vkAllocateMemory");
    imageMemory = handle(device, rawMemory, vkFreeMemory);
    checkVk(vkBindImageMemory(device, rawImage, rawMemory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = rawImage;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView rawView = VK_NULL_HANDLE;
    checkVk(vkCreateImageView(device, &viewInfo, nullptr, &rawView), "vkCreateImageView");
    imageView = handle(device, rawView, vkDestroyImageView);
  }

  VkDescriptorPoolSize poolSizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                       {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2},
                                       {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 3;
  poolInfo.pPoolSizes = poolSizes;
  VkDescriptorPool rawPool = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &rawPool), "descriptor pool");
  auto pool = handle(device, rawPool, vkDestroyDescriptorPool);
  VkDescriptorSetAllocateInfo setAllocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setAllocate.descriptorPool = rawPool;
  setAllocate.descriptorSetCount = 1;
  setAllocate.pSetLayouts = &rawSetLayout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  checkVk(vkAllocateDescriptorSets(device, &setAllocate, &set), "descriptor set");
  VkDescriptorBufferInfo infos[3] = {{frameBuffer.buffer(), 0, VK_WHOLE_SIZE},
                                     {results.buffer(), 0, VK_WHOLE_SIZE},
                                     {cache.buffer(), 0, VK_WHOLE_SIZE}};
  VkDescriptorImageInfo imageDescriptor{VK_NULL_HANDLE, imageView.get(), VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet writes[4];
  for (std::uint32_t i = 0; i < bindingCount; ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = bindings[i].binding;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = bindings[i].descriptorType;
    if (i < 3)
      writes[i].pBufferInfo = &infos[i];
    else
      writes[i].pImageInfo = &imageDescriptor;
  }
  vkUpdateDescriptorSets(device, bindingCount, writes, 0, nullptr);

  context.submitAndWait([&](VkCommandBuffer commands) {
    if (program.image) {
      VkImageMemoryBarrier toGeneral{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      toGeneral.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      toGeneral.newLayout = VK_IMAGE_LAYOUT_GENERAL;
      toGeneral.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
      toGeneral.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      toGeneral.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      toGeneral.image = image.get();
      toGeneral.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                           &toGeneral);
    }
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, rawPipeline);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, rawLayout, 0, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(commands, program.invocations / 64, 1, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
  });
  gpu::Counters counters{};
  results.read(&counters, sizeof counters);
  std::vector<std::uint32_t> words(program.resultWords);
  if (!words.empty())
    results.read(words.data(), words.size() * sizeof(std::uint32_t), sizeof(gpu::Counters));
  return {counters, words};
}

}  // namespace

const char* cacheStressModeName(CacheStressMode mode) {
  switch (mode) {
    case CacheStressMode::Key:
      return "key";
    case CacheStressMode::Counter:
      return "counter";
    case CacheStressMode::ImageKey:
      return "image-key";
    case CacheStressMode::ImageCounter:
      return "image-counter";
    case CacheStressMode::Unprotected:
      return "unprotected";
  }
  return "key";
}

CacheStressResult runCacheStress(const VulkanContext& context, CacheStressMode mode,
                                 std::uint32_t invocations, std::uint32_t iterations) {
  Program program;
  program.body = kStressBody;
  program.invocations = invocations;
  program.image = mode == CacheStressMode::ImageKey || mode == CacheStressMode::ImageCounter;
  program.defines = {"MG_CACHE_TEXEL=1", "MG_CACHE_VALUES=" + std::to_string(kStressValues),
                     "MG_CACHE_PROBE=8",
                     "MG_CACHE_EVICTION=" + std::to_string(gpu::kCacheEvictionRandom),
                     "STRESS_ITERATIONS=" + std::to_string(iterations)};
  if (mode == CacheStressMode::Counter || mode == CacheStressMode::ImageCounter)
    program.defines.push_back("MG_CACHE_UPDATE_COUNTER=1");
  if (mode == CacheStressMode::Unprotected)
    program.defines.push_back("STRESS_UNPROTECTED=1");
  if (program.image) {
    program.defines.push_back("MG_CACHE_ENTRY_WORDS=0");
    program.defines.push_back("STRESS_IMAGE=1");
  }
  auto [counters, words] = runProgram(context, program);
  CacheStressResult result;
  result.mode = mode;
  result.invocations = invocations;
  result.iterations = iterations;
  result.hits = words[0];
  result.torn = words[1];
  result.writes = words[2];
  result.misses = words[3];
  result.occupancy = counters.cacheOccupancy;
  return result;
}

std::vector<std::uint32_t> runCacheProgram(const VulkanContext& context, const std::string& body,
                                           std::vector<std::string> defines, std::uint32_t entries,
                                           std::uint32_t invocations, std::uint64_t clockStart,
                                           std::uint32_t resultWords) {
  Program program;
  program.body = body;
  program.defines = std::move(defines);
  program.entries = entries;
  program.invocations = invocations;
  program.clockStart = clockStart;
  program.resultWords = resultWords;
  return runProgram(context, program).second;
}

}  // namespace memograph::runtime
