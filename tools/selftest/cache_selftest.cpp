#include "tools/selftest/cache_selftest.h"

#include <map>
#include <stdexcept>

#include "runtime/shaders/shared_types.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"
#include "runtime/vk/storage_image.h"
#include "runtime/vk/vulkan_error.h"
#include "runtime/vk/vulkan_handle.h"

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
// No BSDF lobes in this stub (the prelude's MG_OMIT_BSDF_LOBES layout).
#define MG_OMIT_BSDF_LOBES 1
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
#ifdef STRESS_TILE
// One cacheable material of base colour, metallic and roughness (5 values: two image
// texels, an odd fp16 count), each a function of the texel's uv exact in fp16 (texel
// centres k + 0.5 below 64), so a texel stored for another tile or not stored shows.
const uvec4 mg_materialCacheInfo[1] = uvec4[](uvec4(kCacheOutputBaseColor | kCacheOutputMetallic |
                                                    kCacheOutputRoughness, 0x9e3779b9u, 0x7f4a7c15u, 0u));
void evaluateMaterialDirect(uint id, MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  vec2 uv = inputs.uv.v;
  outputs.baseColor = vec3(uv.x, uv.y, uv.x + 2.0 * uv.y + 1.0);
  outputs.metallic = 3.0 * uv.x + uv.y;
  outputs.roughness = 100.0 - uv.y;
}
#include "tile_cache.glsl"
#else
const uvec4 mg_materialCacheInfo[1] = uvec4[](uvec4(0u));
void evaluateMaterialDirect(uint id, MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
}
#include "texel_cache.glsl"
#endif
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
)";

constexpr const char* kMainOpen = R"(
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
    bool hit = cacheData[cacheKeyWord(key.base)] == key.hash;
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i)
      values[i] = uintBitsToFloat(cacheData[offset + kCacheHeader + i]);
    if (!hit) {
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) {
        values[i] = float(k * 16u + i);
        cacheData[offset + kCacheHeader + i] = floatBitsToUint(values[i]);
      }
      cacheData[cacheKeyWord(key.base)] = key.hash;
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

// The subgroup tile fill (tile_cache.glsl tileComputeMissing, thesis §5.4.3) under the
// same contention: STRESS_TILES tiles of one material on the cache's entries. Each
// iteration a lane reads its tile whole (every texel, between the entry protocol's checks);
// the subgroup then computes the tiles its lanes missed, and each served lane checks the
// texel the exchange gave it. results[0..10]: hits, torn, misses, served, wrong served,
// tiles computed, published, given up, duplicates, repack lane-events, fallbacks.
constexpr const char* kTileStressBody = R"(
  uint id = gl_GlobalInvocationID.x;
  g_invocationId = id;
#ifdef STRESS_QUARTER_LANES
  // A partial subgroup, as NVIDIA's raygen often has: a quarter of the lanes computes, so
  // a tile of the subgroup's size takes four passes.
  if ((gl_SubgroupInvocationID & 3u) != 0u) return;
#endif
#ifdef STRESS_ALL_BUT_ONE_LANE
  // All lanes but the last: a tile of the subgroup's size takes a pass of all the others
  // and a pass of one texel.
  if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) return;
#endif
  uvec4 info = mg_materialCacheInfo[0];
  uint localHits = 0u, localTorn = 0u, localMisses = 0u, localServed = 0u, localWrong = 0u;
  for (uint it = 0u; it < uint(STRESS_ITERATIONS); ++it) {
    uint k = cachePcg(id * 7919u + it * 104729u) % uint(STRESS_TILES);
    TileRequest tile;
    tile.level = 0;
    tile.tile = vec2(float(k % 8u), float(k / 8u));
    uint spot = cachePcg(id ^ (it * 0x9e3779b9u)) % kTileTexels;
    tile.local = vec2(float(spot % kTileW) + 0.5, float(spot / kTileW) + 0.5);
    tile.key = cacheKeyOf(info, 0, tile.tile);
    // Every lane runs the same read (a miss reads entry 0 and ignores it), so the lanes need
    // no reconvergence after a divergent branch before the subgroup computation below.
    int entry = cacheFind(tile.key);
    uint readEntry = uint(max(entry, 0));
    uint counterBefore = cacheReadBegin(readEntry, tile.key);
    bool ok = true;
    for (uint t = 0u; t < kTileTexels; ++t) {
      float stored[MG_CACHE_VALUES], expected[MG_CACHE_VALUES];
      tileLoadTexel(readEntry, t, stored);
      stressTexel(tile.tile, t, expected);
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) ok = ok && stored[i] == expected[i];
    }
    bool valid = cacheReadValid(readEntry, tile.key, counterBefore);  // random eviction: no touch
    bool hit = entry >= 0 && valid;
    if (hit && !ok) localTorn += 1u;
    if (hit) localHits += 1u;
    else localMisses += 1u;
#ifdef MG_TILE_TEST_REPACKS
    // The same for the whole subgroup: the pass from which it looks repacked (past the last
    // pass: never).
    g_testRepackPass = it % uint(STRESS_REPACK_PERIOD);
#endif
    MaterialInputs inputs;
    inputs.uv.v = tile.tile * kTileArea + tile.local;
    inputs.uv.x = vec2(1.0, 0.0);
    inputs.uv.y = vec2(0.0, 1.0);
    float values[MG_CACHE_VALUES];
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
    bool served = false;
    tileComputeMissing(!hit, 0u, info, tile, inputs, values, served);
    if (served) {
      localServed += 1u;
      float expected[MG_CACHE_VALUES];
      stressTexel(tile.tile, spot, expected);
      bool ok = true;
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) ok = ok && values[i] == expected[i];
      if (!ok) localWrong += 1u;
    }
  }
  atomicAdd(results[0], localHits);
  atomicAdd(results[1], localTorn);
  atomicAdd(results[2], localMisses);
  atomicAdd(results[3], localServed);
  atomicAdd(results[4], localWrong);
  atomicAdd(results[5], g_tilesComputed);
  atomicAdd(results[6], g_tilesPublished);
  atomicAdd(results[7], g_tilesGivenUp);
  atomicAdd(results[8], g_duplicateTiles);
  atomicAdd(results[9], g_tileRepacks);
  atomicAdd(results[10], g_tileFallbacks);
)";

// Before main() of the tile program: texel t of a tile as the cache must hold it.
constexpr const char* kTileStressFunctions = R"(
void stressTexel(vec2 tile, uint t, out float values[MG_CACHE_VALUES]) {
  MaterialInputs inputs;
  inputs.uv.v = vec2(0.0);
  inputs.uv.x = vec2(0.0);
  inputs.uv.y = vec2(0.0);
  MaterialOutputs outputs;
  evaluateMaterialDirect(0u, tileTexelInputs(inputs, 0, tile, t), outputs);
  cachePack(mg_materialCacheInfo[0].x, outputs, values);
  tileQuantize(values);
}
)";

template <typename T>
VulkanHandle<T> handle(VkDevice device, T raw,
                       void (*destroy)(VkDevice, T, const VkAllocationCallbacks*)) {
  return VulkanHandle<T>(raw, [device, destroy](T object) { destroy(device, object, nullptr); });
}

struct Program {
  std::string body;
  std::string functions;  // GLSL before main()
  std::vector<std::string> defines;
  std::uint32_t entries = kCacheStressEntries;
  std::uint32_t invocations = 64;
  std::uint64_t clockStart = 0;
  std::uint32_t resultWords = 4;
  // A storage image at kBindingTileImage (the texel stress's: 3 rgba32f texels an entry).
  bool image = false;
  VkImageType imageType = VK_IMAGE_TYPE_2D;
  VkFormat imageFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  VkExtent3D imageExtent{0, 0, 0};
  // The tile cache's buffers: kBindingTileTexels (tileTexelWords uints) and kBindingTileLog.
  bool tileBuffers = false;
  std::uint64_t tileTexelWords = 4;
  std::uint32_t tilesPerRow = 0;  // frame.cache.w
  bool readCache = false;         // return the cache's words after the run
};

struct ProgramResult {
  gpu::Counters counters{};
  std::vector<std::uint32_t> words;  // the first resultWords of results[]
  std::vector<std::uint32_t> cache;  // the entries, when readCache
};

// The words of one cache entry, as the program's defines lay it out (texel_cache.glsl).
struct EntryLayout {
  std::uint32_t header = gpu::kCacheEntryHeader;
  std::uint32_t valueWords = 1;
};
EntryLayout entryLayout(const std::vector<std::string>& defines) {
  EntryLayout layout;
  std::uint32_t values = 1;
  bool entryWordsGiven = false, tile = false, deferred = false;
  for (const std::string& d : defines) {
    if (d.rfind("MG_CACHE_VALUES=", 0) == 0)
      values = std::uint32_t(std::stoul(d.substr(16)));
    if (d == "MG_CACHE_UPDATE_COUNTER=1")
      layout.header = gpu::kCacheEntryHeaderWithCounter;
    if (d.rfind("MG_CACHE_ENTRY_WORDS=", 0) == 0) {
      layout.valueWords = std::uint32_t(std::stoul(d.substr(21)));
      entryWordsGiven = true;
    }
    tile = tile || d.rfind("MG_CACHE_TILE=", 0) == 0;
    deferred = deferred || d.rfind("MG_TILE_FILL_DEFERRED=", 0) == 0;
  }
  if (tile && !deferred)
    layout.header += gpu::kCacheEntryTileCountWords;  // texel_cache.glsl kCacheTileCount
  if (!entryWordsGiven)
    layout.valueWords = values;  // fp32 values in the entry
  return layout;
}

// A host-visible storage buffer of `words` zeros (at least one word).
GpuBuffer zeroedBuffer(const VulkanContext& context, std::uint64_t words) {
  std::vector<std::uint32_t> zeros(std::max<std::uint64_t>(words, 1), 0u);
  GpuBuffer buffer =
      hostBuffer(context, zeros.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  buffer.write(zeros.data(), zeros.size() * sizeof(std::uint32_t));
  return buffer;
}

// The program's bindings: frame constants, results, the cache, and the tile cache's buffers
// or storage image where the program uses them.
std::vector<VkDescriptorSetLayoutBinding> programBindings(const Program& program) {
  const auto binding = [](std::uint32_t index, VkDescriptorType type) {
    return VkDescriptorSetLayoutBinding{index, type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  };
  std::vector<VkDescriptorSetLayoutBinding> bindings = {
      binding(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER),
      binding(gpu::kBindingRayCounter, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
      binding(gpu::kBindingCache, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  if (program.tileBuffers) {
    bindings.push_back(binding(gpu::kBindingTileTexels, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER));
    bindings.push_back(binding(gpu::kBindingTileLog, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER));
  }
  if (program.image)
    bindings.push_back(binding(gpu::kBindingTileImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE));
  return bindings;
}

// One program's SPIR-V.
std::vector<std::uint32_t> compileProgram(const Program& program) {
  std::map<std::string, std::string> files = embeddedShaderFiles();
  files["cache_selftest.comp"] =
      std::string(kProgramHead) + program.functions + kMainOpen + program.body + "\n}\n";
  ShaderCompiler compiler(std::move(files), {});
  return compiler.compile({"cache_selftest.comp", ShaderStage::Compute, program.defines});
}

// Compiles and runs one program; returns gpu::Counters, the result words and the cache.
ProgramResult runProgram(const VulkanContext& context, const Program& program) {
  if (program.invocations == 0 || program.invocations % 64 != 0)
    throw std::invalid_argument("cache self-test: invocations must be a positive multiple of 64");
  VkDevice device = context.device();
  std::vector<std::uint32_t> spirv = compileProgram(program);
  const EntryLayout entry = entryLayout(program.defines);
  const std::uint32_t header = entry.header, entryWords = entry.valueWords;

  auto module = createShaderModule(device, spirv);

  const std::vector<VkDescriptorSetLayoutBinding> bindings = programBindings(program);
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = std::uint32_t(bindings.size());
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout rawSetLayout = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &rawSetLayout), "set layout");
  auto setLayout = handle(device, rawSetLayout, vkDestroyDescriptorSetLayout);
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &rawSetLayout;
  VkPipelineLayout rawLayout = VK_NULL_HANDLE;
  checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &rawLayout), "pipeline layout");
  auto layout = handle(device, rawLayout, vkDestroyPipelineLayout);
  auto pipeline = createComputePipeline(context, module.get(), rawLayout, "self-test");

  gpu::FrameConstants frame{};
  frame.cache = glm::uvec4(program.entries, 1u, 0u, program.tilesPerRow);
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
  // The tile cache's texel buffer and its log of published tiles (cleared).
  GpuBuffer tileTexels, tileLog;
  if (program.tileBuffers) {
    tileTexels = zeroedBuffer(context, program.tileTexelWords);
    tileLog = zeroedBuffer(context, gpu::kTileLogEntries);
  }

  StorageImage image;
  if (program.image)
    image = createStorageImage(context, program.imageType, program.imageFormat, program.imageExtent,
                               "self-test image");

  VkDescriptorPoolSize poolSizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                       {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4},
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
  std::map<std::uint32_t, VkDescriptorBufferInfo> bufferInfos = {
      {gpu::kBindingFrame, {frameBuffer.buffer(), 0, VK_WHOLE_SIZE}},
      {gpu::kBindingRayCounter, {results.buffer(), 0, VK_WHOLE_SIZE}},
      {gpu::kBindingCache, {cache.buffer(), 0, VK_WHOLE_SIZE}}};
  if (program.tileBuffers) {
    bufferInfos[gpu::kBindingTileTexels] = {tileTexels.buffer(), 0, VK_WHOLE_SIZE};
    bufferInfos[gpu::kBindingTileLog] = {tileLog.buffer(), 0, VK_WHOLE_SIZE};
  }
  VkDescriptorImageInfo imageDescriptor{VK_NULL_HANDLE, image.view.get(), VK_IMAGE_LAYOUT_GENERAL};
  std::vector<VkWriteDescriptorSet> writes(bindings.size());
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = bindings[i].binding;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = bindings[i].descriptorType;
    if (bindings[i].descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)
      writes[i].pImageInfo = &imageDescriptor;
    else
      writes[i].pBufferInfo = &bufferInfos.at(bindings[i].binding);
  }
  vkUpdateDescriptorSets(device, std::uint32_t(writes.size()), writes.data(), 0, nullptr);

  context.submitAndWait([&](VkCommandBuffer commands) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, rawLayout, 0, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(commands, program.invocations / 64, 1, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
  });
  ProgramResult result;
  results.read(&result.counters, sizeof result.counters);
  result.words.resize(program.resultWords);
  if (!result.words.empty())
    results.read(result.words.data(), result.words.size() * sizeof(std::uint32_t),
                 sizeof(gpu::Counters));
  if (program.readCache) {
    result.cache.resize(emptyCache.size());
    cache.read(result.cache.data(), result.cache.size() * sizeof(std::uint32_t));
  }
  return result;
}

}  // namespace

bool cacheStressModeMustNotTear(CacheStressMode mode) {
  return mode == CacheStressMode::Counter || mode == CacheStressMode::ImageCounter;
}

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

namespace {

Program cacheStressProgram(CacheStressMode mode, std::uint32_t invocations,
                           std::uint32_t iterations) {
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
    program.defines.push_back("MG_CACHE_VALUES_IN_IMAGE=1");
    program.imageExtent = {3 * program.entries, 1, 1};  // 3 rgba32f texels an entry, one row
  }
  return program;
}

}  // namespace

std::vector<std::uint32_t> cacheStressSpirv(CacheStressMode mode) {
  return compileProgram(cacheStressProgram(mode, 64, 1));
}

CacheStressResult runCacheStress(const VulkanContext& context, CacheStressMode mode,
                                 std::uint32_t invocations, std::uint32_t iterations) {
  ProgramResult run = runProgram(context, cacheStressProgram(mode, invocations, iterations));
  const std::vector<std::uint32_t>& words = run.words;
  CacheStressResult result;
  result.mode = mode;
  result.invocations = invocations;
  result.iterations = iterations;
  result.hits = words[0];
  result.torn = words[1];
  result.writes = words[2];
  result.misses = words[3];
  result.occupancy = run.counters.cacheOccupancy;
  return result;
}

std::string TileFillStressResult::failure() const {
  std::string why;
  auto add = [&](bool bad, const std::string& what) {
    if (bad)
      why += (why.empty() ? "" : "; ") + what;
  };
  add(torn > 0, std::to_string(torn) + " torn tile reads");
  add(wrongServed > 0, std::to_string(wrongServed) + " lanes served a wrong texel");
  add(entriesLocked > 0, std::to_string(entriesLocked) + " entries left locked");
  add(countsLeft > 0, std::to_string(countsLeft) + " entries left with a texel count");
  add(tilesPublished + tilesGivenUp != tilesComputed,
      std::to_string(tilesComputed) + " tiles computed, " + std::to_string(tilesPublished) +
          " published + " + std::to_string(tilesGivenUp) + " given up");
  add(occupancy != entriesFilled, "occupancy " + std::to_string(occupancy) + " for " +
                                      std::to_string(entriesFilled) + " entries in use");
  add(tilesPublished == 0 || hits == 0, "nothing published or read");
  add(options.repacks && tilesGivenUp == 0, "nothing given up");
  return why;
}

std::string tileFillStressName(const TileFillStressOptions& options) {
  return std::string("tile-") + tileStorageName(options.storage) +
         (options.lanes == TileFillLanes::Quarter     ? "-quarter"
          : options.lanes == TileFillLanes::AllButOne ? "-allbutone"
                                                      : "") +
         (options.repacks ? "-repacks" : "") + (options.fp16 ? "-fp16" : "") +
         (options.updateCounter ? "" : "-key");
}

std::vector<TileFillStressOptions> tileFillStressConfigurations() {
  std::vector<TileFillStressOptions> all(6);
  all[0].storage = TileStorage::Entry;
  all[1].storage = TileStorage::Entry;
  all[1].lanes = TileFillLanes::AllButOne;
  all[2].storage = TileStorage::Entry;
  all[2].lanes = TileFillLanes::Quarter;
  all[2].repacks = true;
  all[3].storage = TileStorage::Buffer;
  all[3].lanes = TileFillLanes::AllButOne;
  all[3].repacks = all[3].fp16 = true;
  all[4].storage = TileStorage::Texture2D;
  all[4].lanes = TileFillLanes::Quarter;
  all[4].fp16 = true;
  all[5].storage = TileStorage::Texture3D;
  all[5].lanes = TileFillLanes::AllButOne;
  return all;
}

TileFillStressResult runTileFillStress(const VulkanContext& context,
                                       const TileFillStressOptions& options,
                                       std::uint32_t invocations, std::uint32_t iterations) {
  const DeviceInfo& info = context.info();
  const VkSubgroupFeatureFlags needed =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT |
      VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_SHUFFLE_BIT |
      VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  if ((info.subgroupOperations & needed) != needed ||
      !(info.subgroupStages & VK_SHADER_STAGE_COMPUTE_BIT))
    throw std::invalid_argument(
        "the tile fill self-test needs subgroup ballot, shuffle, vote "
        "and arithmetic in compute shaders");
  TileFillStressResult result;
  result.options = options;
  result.invocations = invocations;
  result.iterations = iterations;
  // Subgroup sizes are powers of two: the tile is the subgroup over 4 (4 tiles an iteration)
  // or, fewer lanes computing, the whole subgroup (several passes).
  const std::uint32_t subgroup = std::max(2u, info.subgroupSize);
  const std::uint32_t lanes = options.lanes == TileFillLanes::Quarter ? std::max(1u, subgroup / 4)
                              : options.lanes == TileFillLanes::AllButOne ? subgroup - 1
                                                                          : subgroup;
  const std::uint32_t texels =
      options.lanes == TileFillLanes::All ? std::max(1u, subgroup / 4) : subgroup;
  result.computingLanes = lanes;
  std::uint32_t width = 1;
  while (width * width < texels)
    width *= 2;
  result.tileWidth = width;
  result.tileHeight = std::max(1u, texels / width);
  result.passes = (texels + lanes - 1) / lanes;
  constexpr std::uint32_t kValues = 5, kTiles = 64;
  const std::uint32_t valueWords = options.fp16 ? (kValues + 1) / 2 : kValues;
  const std::uint32_t groups = (kValues + 3) / 4;

  Program program;
  program.body = kTileStressBody;
  program.functions = kTileStressFunctions;
  program.invocations = invocations;
  program.resultWords = 11;
  program.readCache = true;
  program.tileBuffers = true;
  program.tilesPerRow = program.entries;
  const std::uint32_t storage = static_cast<std::uint32_t>(options.storage);
  program.defines = {
      "MG_CACHE_TILE=1",
      "STRESS_TILE=1",
      "MG_CACHE_VALUES=" + std::to_string(kValues),
      "MG_CACHE_PROBE=8",
      "MG_CACHE_EVICTION=" + std::to_string(gpu::kCacheEvictionRandom),
      "MG_CACHE_ENTRY_WORDS=" +
          std::to_string(options.storage == TileStorage::Entry ? texels * valueWords : 0u),
      "MG_TILE_W=" + std::to_string(result.tileWidth),
      "MG_TILE_H=" + std::to_string(result.tileHeight),
      "MG_TILE_STORAGE=" + std::to_string(storage),
      "STRESS_TILES=" + std::to_string(kTiles),
      "STRESS_ITERATIONS=" + std::to_string(iterations)};
  if (options.updateCounter)
    program.defines.push_back("MG_CACHE_UPDATE_COUNTER=1");
  if (options.storage == TileStorage::Texture2D || options.storage == TileStorage::Texture3D)
    program.defines.push_back("MG_CACHE_VALUES_IN_IMAGE=1");  // as cacheShaderDefines does
  if (options.fp16)
    program.defines.push_back("MG_CACHE_VALUE_FP16=1");
  if (options.lanes == TileFillLanes::Quarter)
    program.defines.push_back("STRESS_QUARTER_LANES=1");
  if (options.lanes == TileFillLanes::AllButOne)
    program.defines.push_back("STRESS_ALL_BUT_ONE_LANE=1");
  if (options.repacks) {
    program.defines.push_back("MG_TILE_TEST_REPACKS=1");
    // Given up from pass 0, 1, ... passes - 1, or (two in passes + 2 iterations) never.
    program.defines.push_back("STRESS_REPACK_PERIOD=" + std::to_string(result.passes + 2));
  }
  if (options.storage == TileStorage::Buffer)
    program.tileTexelWords = std::uint64_t(program.entries) * texels * valueWords;
  if (options.storage == TileStorage::Texture2D || options.storage == TileStorage::Texture3D) {
    program.image = true;
    program.imageFormat =
        options.fp16 ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
    program.defines.push_back(options.fp16 ? "MG_TILE_IMAGE_FORMAT=rgba16f"
                                           : "MG_TILE_IMAGE_FORMAT=rgba32f");
    // One row of tiles (tile_cache.glsl tileTexelAt with frame.cache.w = the entries).
    if (options.storage == TileStorage::Texture2D) {
      program.imageExtent = {program.entries * result.tileWidth * groups, result.tileHeight, 1};
    } else {
      program.imageType = VK_IMAGE_TYPE_3D;
      program.imageExtent = {program.entries * result.tileWidth, result.tileHeight, groups};
    }
  }
  ProgramResult run = runProgram(context, program);
  const std::vector<std::uint32_t>& w = run.words;
  result.hits = w[0];
  result.torn = w[1];
  result.misses = w[2];
  result.served = w[3];
  result.wrongServed = w[4];
  result.tilesComputed = w[5];
  result.tilesPublished = w[6];
  result.tilesGivenUp = w[7];
  result.duplicateTiles = w[8];
  result.repacks = w[9];
  result.fallbacks = w[10];
  result.occupancy = run.counters.cacheOccupancy;
  // texel_cache.glsl's layout: the S keys, then each entry's record (clock[, update counter],
  // the tile count, values).
  const std::uint32_t countWord =
      (options.updateCounter ? gpu::kCacheEntryHeaderWithCounter : gpu::kCacheEntryHeader) - 1;
  const std::size_t recordWords = run.cache.size() / program.entries - 1;
  for (std::uint32_t e = 0; e < program.entries; ++e) {
    const std::uint32_t key = run.cache[e];
    result.entriesLocked += key == gpu::kCacheKeyLock;
    result.entriesFilled += key != gpu::kCacheKeyLock && key != gpu::kCacheKeyEmpty;
    result.countsLeft += run.cache[program.entries + e * recordWords + countWord] != 0;
  }
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
  return runProgram(context, program).words;
}

}  // namespace memograph::runtime
