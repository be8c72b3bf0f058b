// The two trace backends on the host side: a compute pipeline running path_tracer.glsl with
// ray queries, or a ray-tracing pipeline running the same source as raygen with the
// report-only hit and miss shaders and its shader-binding table (with, for the callable
// material dispatch, one callable record per scene material). Both share one descriptor
// set layout (shared_types.h bindings).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/materials/material_callables.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/trace/render_stats.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

// The path tracer's descriptor set layout (every binding of shared_types.h) for `stages`;
// `wavefront` adds the wavefront path tracer's path state, queues and control buffer.
VulkanHandle<VkDescriptorSetLayout> createTraceSetLayout(VkDevice device, VkShaderStageFlags stages,
                                                         std::uint32_t textureCount, bool tileImage,
                                                         bool wavefront = false);

// The report-only shaders' compile requests, in appendReportingShaders' order, with their
// stages: for a caller that compiles them beside its other shaders on several threads.
void appendReportingShaderRequests(std::vector<ShaderCompileRequest>& requests,
                                   std::vector<VkShaderStageFlagBits>& stages);

// Appends the report-only shaders (thesis §5.2) of every ray-tracing pipeline here, in this
// order: the closest-hit rays' miss (trace_miss.rmiss), the shadow rays' miss
// (trace_shadow.rmiss) and the closest hit (trace_hit.rchit), with their stages.
void appendReportingShaders(VkDevice device, ShaderCompiler& compiler,
                            std::vector<VulkanHandle<VkShaderModule>>& modules,
                            std::vector<VkShaderStageFlagBits>& stages);

// A ray-tracing pipeline of one group per shader, in `stages` order: a closest-hit shader
// makes a triangle hit group, any other shader a general group (raygen, miss, callable).
// Raygens trace, hit shaders do not (recursion depth 1). `dynamicStack`: the stack size is set
// at each launch (vkCmdSetRayTracingPipelineStackSizeKHR). Created through a deferred
// operation joined by up to `threads` host threads. `what` names it (pipeline statistics).
VulkanHandle<VkPipeline> createRayTracingPipeline(const VulkanContext& context,
                                                  const std::vector<VkShaderModule>& modules,
                                                  const std::vector<VkShaderStageFlagBits>& stages,
                                                  VkPipelineLayout layout, std::uint32_t threads,
                                                  bool dynamicStack, const char* what);

// One region of a shader-binding table: a record for each group listed (a group may repeat).
// A raygen region holds one record, its stride and size the base alignment.
struct ShaderBindingRegion {
  std::vector<std::uint32_t> groups;
  bool raygen = false;
};

// A shader-binding table of `pipeline`'s `groupCount` groups: its buffer, and each region's
// address range in the order given, each base-aligned (an empty region: all zero).
struct ShaderBindingTable {
  GpuBuffer buffer;
  std::vector<VkStridedDeviceAddressRegionKHR> regions;
};
ShaderBindingTable createShaderBindingTable(const VulkanContext& context, VkPipeline pipeline,
                                            std::uint32_t groupCount,
                                            const std::vector<ShaderBindingRegion>& regions);

// What a TracePipeline is built with besides the device, the compiler and the textures.
struct TracePipelineSetup {
  // Null for the switch dispatch (materials.glsl holds every material); else the pipeline
  // backend's callable material shaders (the raygen is then compiled with
  // MG_MATERIAL_CALLABLES).
  const MaterialCallables* callables = nullptr;
  // Host threads that may join the driver's ray-tracing pipeline compile
  // (VK_KHR_deferred_host_operations); 1 creates it on the calling thread alone.
  std::uint32_t pipelineThreads = 1;
  // Query backend: threads compiling the GLSL and creating the compute pipelines (the path
  // tracer's and the tile fill's at once); 0: one per hardware thread.
  std::uint32_t compileThreads = 0;
  // Defines of the path tracer (raygen or compute) only, e.g. the texel cache's.
  std::vector<std::string> defines;
  bool tileImage = false;
  // Also build the deferred tile fill's pass (the same source with MG_TILE_FILL_PASS: a
  // second raygen of this pipeline, or a second compute pipeline).
  bool tileFillPass = false;
};

class TracePipeline {
 public:
  // Throws std::invalid_argument for callables on the query backend.
  TracePipeline(const VulkanContext& context, ShaderCompiler& compiler, std::uint32_t textureCount,
                const TracePipelineSetup& setup = {});

  VkDescriptorSetLayout descriptorSetLayout() const { return setLayout_.get(); }
  // Binds and launches one thread per pixel, tracing the paths `paths` names
  // (PathDispatch::push, runtime/trace/megakernel/path_dispatches.h).
  void record(VkCommandBuffer commands, VkDescriptorSet set, std::uint32_t width,
              std::uint32_t height, const gpu::TraceDispatchPush& paths) const;
  // Binds and launches the deferred tile fill's pass: `rows` rows of
  // gpu::kFillRowInvocations (MaterialCache::tileFillRows); nothing without the pass. The
  // caller orders it after the trace.
  void recordTileFill(VkCommandBuffer commands, VkDescriptorSet set, std::uint32_t rows) const;
  const RayTracingStack& stack() const { return stack_; }

 private:
  const VulkanContext& context_;
  Backend backend_;
  bool tileFillPass_ = false;
  VulkanHandle<VkDescriptorSetLayout> setLayout_;
  VulkanHandle<VkPipelineLayout> layout_;
  VulkanHandle<VkPipeline> pipeline_;
  VulkanHandle<VkPipeline> fillPipeline_;  // query backend: the tile fill's compute pipeline
  GpuBuffer shaderBindingTable_;
  VkStridedDeviceAddressRegionKHR raygenRegion_{};
  VkStridedDeviceAddressRegionKHR missRegion_{};
  VkStridedDeviceAddressRegionKHR hitRegion_{};
  VkStridedDeviceAddressRegionKHR callableRegion_{};
  VkStridedDeviceAddressRegionKHR fillRaygenRegion_{};
  RayTracingStack stack_;

  void bindRayTracing(VkCommandBuffer commands, VkDescriptorSet set) const;
};

}  // namespace memograph::runtime
