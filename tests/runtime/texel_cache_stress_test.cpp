// Concurrency stress test of the texel cache's entry protocol (thesis §5.3.4): a compute
// shader that includes the real texel_cache.glsl hammers a tiny cache (32 entries, D = 8,
// random eviction) with 64 keys whose values are a known function of the key, and checks
// every hit's values. A torn read is a hit whose values belong to another key (the A-B-A
// race the key-only check cannot see). The update-counter check must give none; the
// key-only count is reported, and so is an unprotected protocol's (no lock, no second look)
// to show that tears do happen here.
#include <cstdio>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/gpu_buffer.h"
#include "runtime/shader_compiler.h"
#include "runtime/shader_sources.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/vulkan_context.h"
#include "runtime/vulkan_error.h"
#include "runtime/vulkan_handle.h"

namespace memograph::runtime {
namespace {

constexpr std::uint32_t kEntries = 32;
constexpr std::uint32_t kValues = 12;
constexpr std::uint32_t kInvocations = 4096;

// Stubs for what texel_cache.glsl expects from the path tracer and the material prelude;
// the test calls cacheRead / cacheWrite directly with its own keys.
constexpr const char* kStressShader = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared_types.h"
layout(set = 0, binding = kBindingFrame, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = kBindingRayCounter, std430) buffer ResultBlock {
  Counters counters;  // texel_cache.glsl counts occupancy here
  uint hits; uint torn; uint writes; uint misses;
};
struct float2_D { vec2 v; vec2 x; vec2 y; };
struct MaterialInputs { float2_D uv; };
struct MaterialOutputs {
  vec3 baseColor; float metallic; float roughness; vec3 normal; vec3 emission; float opacity;
  float specular;
};
MaterialOutputs mg_defaultMaterialOutputs(MaterialInputs inputs) {
  MaterialOutputs o;
  o.baseColor = vec3(0.0); o.metallic = 0.0; o.roughness = 0.0; o.normal = vec3(0.0);
  o.emission = vec3(0.0); o.opacity = 1.0; o.specular = 0.5;
  return o;
}
const uvec4 mg_materialCacheInfo[1] = uvec4[](uvec4(0u));
void evaluateMaterialDirect(uint id, MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
}
#include "texel_cache.glsl"
layout(local_size_x = 64) in;
void main() {
  uint id = gl_GlobalInvocationID.x;
  uint localHits = 0u, localTorn = 0u, localWrites = 0u, localMisses = 0u;
  for (uint it = 0u; it < uint(STRESS_ITERATIONS); ++it) {
    uint k = cachePcg(id * 7919u + it * 104729u) % 64u;
    CacheKey key;
    key.hash = k + 1u;
    key.base = cachePcg(k ^ 0x5bd1e995u) % (frame.cache.x - uint(MG_CACHE_PROBE));
    float values[MG_CACHE_VALUES];
#ifdef STRESS_UNPROTECTED
    // No lock and no second look: shows that this device and harness can tear at all.
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
    if (cacheRead(key, values)) {
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
      cacheWrite(key, values);
#endif
      localWrites += 1u;
    }
  }
  atomicAdd(hits, localHits);
  atomicAdd(torn, localTorn);
  atomicAdd(writes, localWrites);
  atomicAdd(misses, localMisses);
}
)";

struct StressResult {
  std::uint32_t hits = 0, torn = 0, writes = 0, misses = 0;
  std::uint32_t occupancy = 0;  // not in the shader's block: read from gpu::Counters
  std::uint32_t filled = 0;     // non-empty keys in the cache after the run
};

// mode: 0 the key check, 1 the update counter, 2 unprotected (no lock, no check).
StressResult runStress(const VulkanContext& context, int mode, std::uint32_t iterations) {
  const bool updateCounter = mode == 1;
  VkDevice device = context.device();
  std::map<std::string, std::string> files;
  for (const auto& shader : embeddedShaders())
    files[std::string(shader.name)] = std::string(shader.text);
  files["cache_stress.comp"] = kStressShader;
  ShaderCompiler compiler(std::move(files), {});
  std::vector<std::string> defines = {
      "MG_CACHE_TEXEL=1", "MG_CACHE_VALUES=" + std::to_string(kValues), "MG_CACHE_PROBE=8",
      "MG_CACHE_EVICTION=" + std::to_string(gpu::kCacheEvictionRandom),
      "STRESS_ITERATIONS=" + std::to_string(iterations)};
  if (updateCounter)
    defines.push_back("MG_CACHE_UPDATE_COUNTER=1");
  if (mode == 2)
    defines.push_back("STRESS_UNPROTECTED=1");
  std::vector<std::uint32_t> spirv =
      compiler.compile({"cache_stress.comp", ShaderStage::Compute, defines});

  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size() * sizeof(std::uint32_t);
  moduleInfo.pCode = spirv.data();
  VkShaderModule rawModule = VK_NULL_HANDLE;
  checkVk(vkCreateShaderModule(device, &moduleInfo, nullptr, &rawModule), "vkCreateShaderModule");
  VulkanHandle<VkShaderModule> module(
      rawModule, [device](VkShaderModule m) { vkDestroyShaderModule(device, m, nullptr); });

  VkDescriptorSetLayoutBinding bindings[3] = {
      {gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {gpu::kBindingRayCounter, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {gpu::kBindingCache, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr}};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 3;
  setInfo.pBindings = bindings;
  VkDescriptorSetLayout rawSetLayout = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &rawSetLayout), "set layout");
  VulkanHandle<VkDescriptorSetLayout> setLayout(rawSetLayout, [device](VkDescriptorSetLayout l) {
    vkDestroyDescriptorSetLayout(device, l, nullptr);
  });
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &rawSetLayout;
  VkPipelineLayout rawLayout = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &rawLayout), "pipeline layout");
  VulkanHandle<VkPipelineLayout> layout(
      rawLayout, [device](VkPipelineLayout l) { vkDestroyPipelineLayout(device, l, nullptr); });
  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = rawModule;
  pipelineInfo.stage.pName = "main";
  pipelineInfo.layout = rawLayout;
  VkPipeline rawPipeline = VK_NULL_HANDLE;
  checkVk(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &rawPipeline),
          "compute pipeline");
  VulkanHandle<VkPipeline> pipeline(
      rawPipeline, [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });

  const std::uint32_t header =
      updateCounter ? gpu::kCacheEntryHeaderWithCounter : gpu::kCacheEntryHeader;
  gpu::FrameConstants frame{};
  frame.cache = glm::uvec4(kEntries, 1u, 0u, 0u);
  GpuBuffer frameBuffer = hostBuffer(context, sizeof frame, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  frameBuffer.write(&frame, sizeof frame);
  // gpu::Counters, then the test's counts.
  std::vector<std::uint8_t> zero(sizeof(gpu::Counters) + sizeof(StressResult), 0);
  GpuBuffer results = hostBuffer(context, zero.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  results.write(zero.data(), zero.size());
  std::vector<std::uint32_t> emptyCache(std::size_t(kEntries) * (header + kValues), 0u);
  GpuBuffer cache = hostBuffer(context, emptyCache.size() * sizeof(std::uint32_t),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  cache.write(emptyCache.data(), emptyCache.size() * sizeof(std::uint32_t));

  VkDescriptorPoolSize poolSizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                       {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = poolSizes;
  VkDescriptorPool rawPool = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &rawPool), "descriptor pool");
  VulkanHandle<VkDescriptorPool> pool(
      rawPool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });
  VkDescriptorSetAllocateInfo allocateInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocateInfo.descriptorPool = rawPool;
  allocateInfo.descriptorSetCount = 1;
  allocateInfo.pSetLayouts = &rawSetLayout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  checkVk(vkAllocateDescriptorSets(device, &allocateInfo, &set), "descriptor set");
  VkDescriptorBufferInfo infos[3] = {{frameBuffer.buffer(), 0, VK_WHOLE_SIZE},
                                     {results.buffer(), 0, VK_WHOLE_SIZE},
                                     {cache.buffer(), 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[3];
  for (int i = 0; i < 3; ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = bindings[i].binding;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = bindings[i].descriptorType;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(device, 3, writes, 0, nullptr);

  context.submitAndWait([&](VkCommandBuffer commands) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, rawPipeline);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, rawLayout, 0, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(commands, kInvocations / 64, 1, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
  });
  StressResult result;
  results.read(&result, sizeof result, sizeof(gpu::Counters));
  gpu::Counters counters{};
  results.read(&counters, sizeof counters);
  result.occupancy = counters.cacheOccupancy;
  std::vector<std::uint32_t> finalCache(emptyCache.size());
  cache.read(finalCache.data(), finalCache.size() * sizeof(std::uint32_t));
  for (std::uint32_t e = 0; e < kEntries; ++e)
    result.filled += finalCache[std::size_t(e) * (header + kValues)] != gpu::kCacheKeyEmpty;
  return result;
}

TEST(TexelCacheStress, UpdateCounterGivesNoTornReads) {
  testing::testOptions();  // sets XDG_RUNTIME_DIR when unset
  ContextOptions options;
  options.validation = validationLayerAvailable();
  VulkanContext context(options);
  const std::uint32_t iterations = 256;
  StressResult key = runStress(context, 0, iterations);
  StressResult counter = runStress(context, 1, iterations);
  StressResult unprotected = runStress(context, 2, iterations);
  for (const auto& [name, r] :
       {std::pair{"key", key}, std::pair{"counter", counter}, std::pair{"no", unprotected}}) {
    std::printf(
        "cache stress (%s check, %u invocations x %u, 64 keys, 32 entries): %u hits, "
        "%u misses, %u torn reads\n",
        name, kInvocations, iterations, r.hits, r.misses, r.torn);
    EXPECT_EQ(r.hits + r.misses, kInvocations * iterations);
    EXPECT_GT(r.hits, 0u);
    EXPECT_GT(r.misses, 0u);
  }
  // The occupancy counter counts each entry's first fill once: it equals the entries left
  // non-empty (a key never returns to empty) under thousands of racing writers.
  for (const StressResult& r : {key, counter}) {
    std::printf("cache stress: occupancy counter %u, non-empty entries %u of %u\n", r.occupancy,
                r.filled, kEntries);
    EXPECT_EQ(r.occupancy, r.filled);
    EXPECT_GT(r.filled, 0u);
  }
  EXPECT_EQ(counter.torn, 0u);
  // The unprotected protocol's tears show that the harness can see a tear on this device
  // (lavapipe: 21000 to 44000 of about 360000 hits); reported, not asserted, since it depends on
  // the device's scheduling. The key-only check is reported too (lavapipe: 0).
}

}  // namespace
}  // namespace memograph::runtime
