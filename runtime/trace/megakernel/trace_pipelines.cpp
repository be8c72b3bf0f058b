#include "runtime/trace/megakernel/trace_pipelines.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "runtime/host/parallel_for.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

// vkCreateRayTracingPipelinesKHR, with the context's pipeline cache, through a deferred
// operation joined by up to `threads` host threads: a driver that compiles the pipeline's
// shaders itself (one per material with callables) can then compile them in parallel. A
// driver that does not defer simply creates the pipeline in the call.
VkPipeline createWithDeferredOperation(const VulkanContext& context,
                                       const VkRayTracingPipelineCreateInfoKHR& info,
                                       std::uint32_t threads) {
  VkDevice device = context.device();
  const DeviceFunctions& f = context.functions();
  VkDeferredOperationKHR operation = VK_NULL_HANDLE;
  if (threads > 1)
    checkVk(f.createDeferredOperation(device, nullptr, &operation), "vkCreateDeferredOperationKHR");
  VulkanHandle<VkDeferredOperationKHR> owned(operation, [device, &f](VkDeferredOperationKHR op) {
    if (op != VK_NULL_HANDLE)
      f.destroyDeferredOperation(device, op, nullptr);
  });
  VkRayTracingPipelineCreateInfoKHR withFeedback = info;
  PipelineCreationFeedback feedback(context, info.stageCount);
  withFeedback.pNext = feedback.chain(info.pNext);
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result = f.createRayTracingPipelines(device, operation, context.pipelineCache().handle(),
                                                1, &withFeedback, nullptr, &pipeline);
  if (result == VK_OPERATION_DEFERRED_KHR) {
    std::uint32_t concurrency = f.getDeferredOperationMaxConcurrency(device, operation);
    std::uint32_t count = std::max(1u, std::min(threads, concurrency));
    auto join = [&] {
      // VK_THREAD_IDLE_KHR: nothing to do right now, but the operation is not done.
      while (f.deferredOperationJoin(device, operation) == VK_THREAD_IDLE_KHR)
        std::this_thread::yield();
    };
    std::vector<std::thread> helpers;
    for (std::uint32_t i = 1; i < count; ++i)
      helpers.emplace_back(join);
    join();
    for (auto& helper : helpers)
      helper.join();
    result = f.getDeferredOperationResult(device, operation);
  } else if (result == VK_OPERATION_NOT_DEFERRED_KHR) {
    result = VK_SUCCESS;
  }
  checkVk(result, "vkCreateRayTracingPipelinesKHR");
  feedback.count();  // written once the (deferred) creation has completed
  return pipeline;
}

}  // namespace

void appendReportingShaderRequests(std::vector<ShaderCompileRequest>& requests,
                                   std::vector<VkShaderStageFlagBits>& stages) {
  requests.push_back({"trace_miss.rmiss", ShaderStage::Miss, {}});
  requests.push_back({"trace_shadow.rmiss", ShaderStage::Miss, {}});
  requests.push_back({"trace_hit.rchit", ShaderStage::ClosestHit, {}});
  stages.insert(stages.end(), {VK_SHADER_STAGE_MISS_BIT_KHR, VK_SHADER_STAGE_MISS_BIT_KHR,
                               VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR});
}

void appendReportingShaders(VkDevice device, ShaderCompiler& compiler,
                            std::vector<VulkanHandle<VkShaderModule>>& modules,
                            std::vector<VkShaderStageFlagBits>& stages) {
  std::vector<ShaderCompileRequest> requests;
  appendReportingShaderRequests(requests, stages);
  for (const ShaderCompileRequest& request : requests)
    modules.push_back(createShaderModule(device, compiler.compile(request)));
}

VulkanHandle<VkPipeline> createRayTracingPipeline(const VulkanContext& context,
                                                  const std::vector<VkShaderModule>& modules,
                                                  const std::vector<VkShaderStageFlagBits>& stages,
                                                  VkPipelineLayout layout, std::uint32_t threads,
                                                  bool dynamicStack, const char* what) {
  const auto shaderCount = static_cast<std::uint32_t>(modules.size());
  std::vector<VkPipelineShaderStageCreateInfo> shaderStages(shaderCount);
  std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups(shaderCount);
  for (std::uint32_t i = 0; i < shaderCount; ++i) {
    shaderStages[i] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    shaderStages[i].stage = stages[i];
    shaderStages[i].module = modules[i];
    shaderStages[i].pName = "main";
    groups[i] = {VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    groups[i].generalShader = VK_SHADER_UNUSED_KHR;
    groups[i].closestHitShader = VK_SHADER_UNUSED_KHR;
    groups[i].anyHitShader = VK_SHADER_UNUSED_KHR;
    groups[i].intersectionShader = VK_SHADER_UNUSED_KHR;
    if (stages[i] == VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR) {
      groups[i].type = VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
      groups[i].closestHitShader = i;
    } else {
      groups[i].type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
      groups[i].generalShader = i;
    }
  }
  VkRayTracingPipelineCreateInfoKHR info{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  info.stageCount = shaderCount;
  info.pStages = shaderStages.data();
  info.groupCount = shaderCount;
  info.pGroups = groups.data();
  // Raygens trace; hit shaders never do. Callables do not count towards recursion.
  info.maxPipelineRayRecursionDepth = 1;
  info.layout = layout;
  const VkDynamicState stackState = VK_DYNAMIC_STATE_RAY_TRACING_PIPELINE_STACK_SIZE_KHR;
  VkPipelineDynamicStateCreateInfo dynamicState{
      VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamicState.dynamicStateCount = 1;
  dynamicState.pDynamicStates = &stackState;
  if (dynamicStack)
    info.pDynamicState = &dynamicState;
  PipelineStatistics* statistics = context.pipelineStatistics();
  if (statistics)
    info.flags |= PipelineStatistics::captureFlags();
  VkDevice device = context.device();
  VulkanHandle<VkPipeline> pipeline(
      createWithDeferredOperation(context, info, threads),
      [device](VkPipeline p) { vkDestroyPipeline(device, p, nullptr); });
  if (statistics)
    statistics->record(pipeline.get(), what);
  return pipeline;
}

ShaderBindingTable createShaderBindingTable(const VulkanContext& context, VkPipeline pipeline,
                                            std::uint32_t groupCount,
                                            const std::vector<ShaderBindingRegion>& regions) {
  const auto& rt = context.info().rayTracingProperties;
  const std::uint32_t handleSize = rt.shaderGroupHandleSize;
  const VkDeviceSize stride = alignUp(handleSize, rt.shaderGroupHandleAlignment);
  const VkDeviceSize base = rt.shaderGroupBaseAlignment;
  std::vector<std::uint8_t> handles(std::size_t(handleSize) * groupCount);
  checkVk(context.functions().getRayTracingShaderGroupHandles(
              context.device(), pipeline, 0, groupCount, handles.size(), handles.data()),
          "vkGetRayTracingShaderGroupHandlesKHR");
  // Each region's offset and record stride, then the records' bytes.
  std::vector<VkDeviceSize> offsets, strides;
  VkDeviceSize end = 0;
  for (const auto& region : regions) {
    const VkDeviceSize offset = alignUp(end, base);
    offsets.push_back(offset);
    strides.push_back(region.raygen ? alignUp(stride, base) : stride);
    if (!region.groups.empty())
      end = offset + (region.raygen ? alignUp(stride, base) : region.groups.size() * stride);
  }
  std::vector<std::uint8_t> table(end, 0);
  for (std::size_t r = 0; r < regions.size(); ++r)
    for (std::size_t i = 0; i < regions[r].groups.size(); ++i)
      std::memcpy(&table[offsets[r] + i * strides[r]],
                  &handles[std::size_t(regions[r].groups[i]) * handleSize], handleSize);
  ShaderBindingTable sbt;
  sbt.buffer = GpuBuffer(
      context, end + base,
      VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  const VkDeviceAddress address = alignUp(sbt.buffer.address(), base);
  sbt.buffer.write(table.data(), table.size(), address - sbt.buffer.address());
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const VkDeviceSize records = regions[r].raygen ? 1 : regions[r].groups.size();
    sbt.regions.push_back(regions[r].groups.empty()
                              ? VkStridedDeviceAddressRegionKHR{}
                              : VkStridedDeviceAddressRegionKHR{address + offsets[r], strides[r],
                                                                records * strides[r]});
  }
  return sbt;
}

VulkanHandle<VkDescriptorSetLayout> createTraceSetLayout(VkDevice device, VkShaderStageFlags stages,
                                                         std::uint32_t textureCount, bool tileImage,
                                                         bool wavefront) {
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
  add(gpu::kBindingCache, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingTileTexels, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingTileLog, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingTileQueue, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingHitFeedback, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  add(gpu::kBindingCountingBoxes, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR);
  if (tileImage)
    add(gpu::kBindingTileImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  if (wavefront) {
    add(gpu::kBindingPathState, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    add(gpu::kBindingPathQueues, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    add(gpu::kBindingWavefrontControl, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  }
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout),
          "vkCreateDescriptorSetLayout");
  return VulkanHandle<VkDescriptorSetLayout>(setLayout, [device](VkDescriptorSetLayout l) {
    vkDestroyDescriptorSetLayout(device, l, nullptr);
  });
}

TracePipeline::TracePipeline(const VulkanContext& context, ShaderCompiler& compiler,
                             std::uint32_t textureCount, const TracePipelineSetup& setup)
    : context_(context), backend_(context.backend()), tileFillPass_(setup.tileFillPass) {
  VkDevice device = context.device();
  bool query = backend_ == Backend::RayQuery;
  const MaterialCallables* callables = setup.callables;
  const bool tileFillPass = setup.tileFillPass;
  if (query && callables)
    throw std::invalid_argument(
        "callable material shaders need the ray-tracing pipeline backend (--backend pipeline); "
        "the query backend dispatches materials with a switch");
  // Callables read the textures (mg_SampleTexture) through the same set as the raygen.
  VkShaderStageFlags stages =
      query ? VK_SHADER_STAGE_COMPUTE_BIT
            : VK_SHADER_STAGE_RAYGEN_BIT_KHR | (callables ? VK_SHADER_STAGE_CALLABLE_BIT_KHR : 0);

  setLayout_ = createTraceSetLayout(device, stages, textureCount, setup.tileImage);
  VkDescriptorSetLayout setLayout = setLayout_.get();

  // The raygen (or the query backend's compute shader) reads which paths a dispatch traces.
  layout_ = createPipelineLayout(
      device, setLayout, query ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_RAYGEN_BIT_KHR,
      sizeof(gpu::TraceDispatchPush));
  VkPipelineLayout layout = layout_.get();

  std::vector<std::string> defines = {"MG_TEXTURE_COUNT=" + std::to_string(textureCount),
                                      query ? "MG_BACKEND_QUERY=1" : "MG_BACKEND_PIPELINE=1"};
  if (context.info().subgroupArithmeticStages &
      (query ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_RAYGEN_BIT_KHR))
    defines.push_back("MG_SUBGROUP_RAY_COUNT=1");
  std::uint32_t materialRecords = 0;
  if (callables) {
    materialRecords = static_cast<std::uint32_t>(callables->shaderForMaterial.size());
    defines.push_back("MG_MATERIAL_CALLABLES=1");
    defines.push_back("MG_MATERIAL_COUNT=" + std::to_string(materialRecords));
  }
  defines.insert(defines.end(), setup.defines.begin(), setup.defines.end());
  // The deferred tile fill's pass: the same source and defines, entered at the fill.
  std::vector<std::string> fillDefines = defines;
  fillDefines.push_back("MG_TILE_FILL_PASS=1");

  if (query) {
    // The path tracer and the tile fill: both compiled, then both pipelines created at once.
    std::vector<ShaderCompileRequest> requests = {
        {"path_tracer.glsl", ShaderStage::Compute, defines}};
    if (tileFillPass)
      requests.push_back({"path_tracer.glsl", ShaderStage::Compute, fillDefines});
    const auto spirv = compiler.compileAll(requests, setup.compileThreads);
    parallelFor(spirv.size(), setup.compileThreads, [&](std::size_t i, std::uint32_t) {
      auto module = createShaderModule(device, spirv[i]);
      (i == 0 ? pipeline_ : fillPipeline_) = createComputePipeline(
          context, module.get(), layout, i == 0 ? "path tracer" : "tile fill");
    });
    return;
  }

  // Ray-tracing pipeline: raygen (the path tracer), two misses, one triangle hit group, the
  // deferred tile fill's raygen when asked for, then one general group per callable
  // material shader (the fill calls them too).
  const std::uint32_t callableCount =
      callables ? static_cast<std::uint32_t>(callables->spirv.size()) : 0;
  const std::uint32_t firstCallable = tileFillPass ? 5 : 4;
  const std::uint32_t shaderCount = firstCallable + callableCount;
  std::vector<VulkanHandle<VkShaderModule>> modules;
  modules.push_back(createShaderModule(
      device, compiler.compile({"path_tracer.glsl", ShaderStage::RayGen, defines})));
  std::vector<VkShaderStageFlagBits> stageBits = {VK_SHADER_STAGE_RAYGEN_BIT_KHR};
  appendReportingShaders(device, compiler, modules, stageBits);
  if (tileFillPass) {
    modules.push_back(createShaderModule(
        device, compiler.compile({"path_tracer.glsl", ShaderStage::RayGen, fillDefines})));
    stageBits.push_back(VK_SHADER_STAGE_RAYGEN_BIT_KHR);
  }
  for (std::uint32_t i = 0; i < callableCount; ++i) {
    modules.push_back(createShaderModule(device, callables->spirv[i]));
    stageBits.push_back(VK_SHADER_STAGE_CALLABLE_BIT_KHR);
  }
  std::vector<VkShaderModule> moduleHandles;
  for (const auto& module : modules)
    moduleHandles.push_back(module.get());
  // The stack size is set per launch (below), not left to the spec's default.
  pipeline_ = createRayTracingPipeline(context, moduleHandles, stageBits, layout,
                                       setup.pipelineThreads, true, "megakernel");
  VkPipeline pipeline = pipeline_.get();

  // The pipeline stack. The spec's default assumes callables may be called from hit and
  // miss shaders while a ray is traced (raygen + max(hit, miss) + 2 x the largest callable).
  // Here only the raygens call callables, never while a trace is in flight, and neither
  // hits, misses nor callables call anything: raygen + max(hit, miss, callable) is enough.
  const auto groupStack = [&](std::uint32_t group, VkShaderGroupShaderKHR shader) {
    return static_cast<std::uint32_t>(
        context.functions().getRayTracingShaderGroupStackSize(device, pipeline, group, shader));
  };
  stack_.raygen = groupStack(0, VK_SHADER_GROUP_SHADER_GENERAL_KHR);
  if (tileFillPass)
    stack_.raygen = std::max(stack_.raygen, groupStack(4, VK_SHADER_GROUP_SHADER_GENERAL_KHR));
  stack_.miss = std::max(groupStack(1, VK_SHADER_GROUP_SHADER_GENERAL_KHR),
                         groupStack(2, VK_SHADER_GROUP_SHADER_GENERAL_KHR));
  stack_.closestHit = groupStack(3, VK_SHADER_GROUP_SHADER_CLOSEST_HIT_KHR);
  for (std::uint32_t i = 0; i < callableCount; ++i)
    stack_.callableMax = std::max(
        stack_.callableMax, groupStack(firstCallable + i, VK_SHADER_GROUP_SHADER_GENERAL_KHR));
  const std::uint32_t traced = std::max(stack_.closestHit, stack_.miss);
  stack_.driverDefault = stack_.raygen + traced + 2 * stack_.callableMax;
  stack_.pipeline = stack_.raygen + std::max(traced, stack_.callableMax);

  // Shader-binding table: [raygen][miss, shadow miss][hit][fill raygen][callable per
  // material id], each region base-aligned. Scene materials sharing a graph point at the
  // same callable group.
  std::vector<std::uint32_t> callableGroups;
  for (std::uint32_t m = 0; m < materialRecords; ++m)
    callableGroups.push_back(firstCallable + callables->shaderForMaterial[m]);
  ShaderBindingTable table = createShaderBindingTable(
      context, pipeline, shaderCount,
      {{{0}, true},
       {{1, 2}},
       {{3}},
       {tileFillPass ? std::vector<std::uint32_t>{4} : std::vector<std::uint32_t>{}, true},
       {callableGroups}});
  shaderBindingTable_ = std::move(table.buffer);
  raygenRegion_ = table.regions[0];
  missRegion_ = table.regions[1];
  hitRegion_ = table.regions[2];
  fillRaygenRegion_ = table.regions[3];
  callableRegion_ = table.regions[4];
}

void TracePipeline::record(VkCommandBuffer commands, VkDescriptorSet set, std::uint32_t width,
                           std::uint32_t height, const gpu::TraceDispatchPush& paths) const {
  if (backend_ == Backend::RayQuery) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(commands, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof paths,
                       &paths);
    vkCmdDispatch(commands, (width + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize,
                  (height + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize, 1);
    return;
  }
  bindRayTracing(commands, set);
  vkCmdPushConstants(commands, layout_.get(), VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof paths,
                     &paths);
  context_.functions().cmdTraceRays(commands, &raygenRegion_, &missRegion_, &hitRegion_,
                                    &callableRegion_, width, height, 1);
}

void TracePipeline::bindRayTracing(VkCommandBuffer commands, VkDescriptorSet set) const {
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_.get());
  context_.functions().cmdSetRayTracingPipelineStackSize(commands, stack_.pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, layout_.get(), 0, 1,
                          &set, 0, nullptr);
}

// `rows` rows of kFillRowInvocations invocations, one per texel of every queue slot (from
// MaterialCache::tileFillRows); the slots past the frame's count return at once (a fixed
// launch needs no count read back or indirect dispatch: about a million empty invocations
// for the default 65536 4x4 slots).
void TracePipeline::recordTileFill(VkCommandBuffer commands, VkDescriptorSet set,
                                   std::uint32_t rows) const {
  if (!tileFillPass_ || rows == 0)
    return;
  if (backend_ == Backend::RayQuery) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, fillPipeline_.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(commands, gpu::kFillRowInvocations / gpu::kFillWorkgroupSize, rows, 1);
    return;
  }
  bindRayTracing(commands, set);
  context_.functions().cmdTraceRays(commands, &fillRaygenRegion_, &missRegion_, &hitRegion_,
                                    &callableRegion_, gpu::kFillRowInvocations, rows, 1);
}

}  // namespace memograph::runtime
