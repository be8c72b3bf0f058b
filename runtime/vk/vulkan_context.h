// The headless Vulkan context: instance (with validation when asked), the chosen physical
// device (a discrete GPU, else any device with ray tracing, e.g. lavapipe), one compute
// queue, and the extension entry points the renderer calls.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/pipeline_cache.h"
#include "runtime/vk/pipeline_statistics.h"
#include "runtime/vk/vulkan_handle.h"

namespace memograph::runtime {

struct ValidationLog;  // validation-layer errors collected by the debug messenger

enum class Backend { Auto, RayQuery, RayTracingPipeline };

const char* backendName(Backend backend);
// Parses "auto", "query" or "pipeline"; throws std::invalid_argument naming the choices.
Backend parseBackend(const std::string& text);

struct ContextOptions {
  int deviceIndex = -1;     // index into vkEnumeratePhysicalDevices; -1 picks one
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation (error if missing)
  Backend backend = Backend::Auto;
  // With Backend::Auto: take the pipeline backend when the device has it, else ray query.
  // Set for scenes with many materials, where per-material callables keep shaders small.
  bool autoPrefersPipeline = false;
  // Where the device's pipeline cache file is kept (PipelineCache; the Renderer puts it in
  // the shader cache's folder). Empty: no pipeline cache.
  std::filesystem::path pipelineCacheDirectory;
  // Keep the driver's statistics of every pipeline (PipelineStatistics: registers, spills,
  // ...). The device must have VK_KHR_pipeline_executable_properties, else the constructor
  // throws saying so.
  bool pipelineStatistics = false;
};

// Entry points of device extensions, loaded per device (no global dispatch state).
struct DeviceFunctions {
  PFN_vkCreateAccelerationStructureKHR createAccelerationStructure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroyAccelerationStructure = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR getAccelerationStructureBuildSizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmdBuildAccelerationStructures = nullptr;
  PFN_vkCmdCopyAccelerationStructureKHR cmdCopyAccelerationStructure = nullptr;
  PFN_vkCmdWriteAccelerationStructuresPropertiesKHR cmdWriteAccelerationStructuresProperties =
      nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR getAccelerationStructureDeviceAddress = nullptr;
  PFN_vkCreateRayTracingPipelinesKHR createRayTracingPipelines = nullptr;
  PFN_vkGetRayTracingShaderGroupHandlesKHR getRayTracingShaderGroupHandles = nullptr;
  PFN_vkCmdTraceRaysKHR cmdTraceRays = nullptr;
  // Where the device has rayTracingPipelineTraceRaysIndirect (the wavefront's trace passes).
  PFN_vkCmdTraceRaysIndirectKHR cmdTraceRaysIndirect = nullptr;
  PFN_vkGetRayTracingShaderGroupStackSizeKHR getRayTracingShaderGroupStackSize = nullptr;
  PFN_vkCmdSetRayTracingPipelineStackSizeKHR cmdSetRayTracingPipelineStackSize = nullptr;
  // VK_KHR_deferred_host_operations (always enabled with acceleration structures): lets
  // ray-tracing pipeline creation use several host threads.
  PFN_vkCreateDeferredOperationKHR createDeferredOperation = nullptr;
  PFN_vkDestroyDeferredOperationKHR destroyDeferredOperation = nullptr;
  PFN_vkGetDeferredOperationMaxConcurrencyKHR getDeferredOperationMaxConcurrency = nullptr;
  PFN_vkGetDeferredOperationResultKHR getDeferredOperationResult = nullptr;
  PFN_vkDeferredOperationJoinKHR deferredOperationJoin = nullptr;
};

struct DeviceInfo {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::uint32_t apiVersion = 0;
  bool rayQuery = false;
  bool rayTracingPipeline = false;
  // vkCmdTraceRaysIndirectKHR enabled (pipeline backend): launch sizes read from a buffer.
  bool traceRaysIndirect = false;
  float timestampPeriodNs = 1.0f;
  bool timestamps = false;
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rayTracingProperties{};
  std::uint32_t minAccelerationStructureScratchOffsetAlignment = 1;
  std::uint32_t subgroupSize = 1;
  // Stages with basic + arithmetic subgroup operations (lavapipe: not ray-tracing stages).
  VkShaderStageFlags subgroupArithmeticStages = 0;
  // All subgroup operations and the stages that have them (the tile cache's check).
  VkSubgroupFeatureFlags subgroupOperations = 0;
  VkShaderStageFlags subgroupStages = 0;
  VkPhysicalDeviceLimits limits{};
  // The largest single allocation (Vulkan 1.1, VkPhysicalDeviceMaintenance3Properties):
  // lavapipe's is 2 GiB, and it crashed on a larger one instead of failing.
  VkDeviceSize maxMemoryAllocationSize = 0;
  // shaderInt64 and shaderBufferInt64Atomics, enabled when present: the texel cache's 64-bit
  // counter clock (thesis §5.3.3) needs both.
  bool bufferInt64Atomics = false;
  // VK_EXT_pipeline_creation_feedback enabled: pipelines say whether the driver found them in
  // the pipeline cache.
  bool pipelineCreationFeedback = false;
};

// Names and ray-tracing support of every device, for --list-devices and error messages.
std::vector<std::string> describeDevices();

// The device a VulkanContext made with `options` would choose, read through an instance
// alone (no device is created): its name, type and properties (limits, largest allocation,
// subgroup size), so that work done before the context exists can be bounded by them. The
// feature fields stay unset. Nothing where no device qualifies; the constructor says why.
std::optional<DeviceInfo> peekDeviceInfo(const ContextOptions& options);

// Whether VK_LAYER_KHRONOS_validation is installed (tests turn validation on when it is).
bool validationLayerAvailable();

class VulkanContext {
 public:
  explicit VulkanContext(const ContextOptions& options);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queueFamily_; }
  const DeviceFunctions& functions() const { return functions_; }
  const DeviceInfo& info() const { return info_; }
  // The backend chosen from the requested one and what the device supports.
  Backend backend() const { return backend_; }
  // The device's pipeline cache: every pipeline is created with it (handle() is
  // VK_NULL_HANDLE without a folder). Thread-safe; the renderer saves it after creating its
  // pipelines.
  PipelineCache& pipelineCache() const { return *pipelineCache_; }
  // The pipelines' statistics where ContextOptions::pipelineStatistics asked for them, else
  // nullptr. Every pipeline creation adds PipelineStatistics::captureFlags() and record()s.
  PipelineStatistics* pipelineStatistics() const { return pipelineStatistics_.get(); }

  // Validation-layer errors seen so far (empty without validation).
  std::vector<std::string> validationErrors() const;

  std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags properties) const;

  // Records with `record` into a fresh command buffer, submits it and waits.
  template <typename Record>
  void submitAndWait(Record&& record) const {
    VkCommandBuffer commands = beginOneTimeCommands();
    record(commands);
    endOneTimeCommands(commands);
  }

  VkCommandBuffer beginOneTimeCommands() const;
  void endOneTimeCommands(VkCommandBuffer commands) const;

 private:
  std::unique_ptr<ValidationLog> validationLog_;
  VulkanHandle<VkInstance> instance_;
  VulkanHandle<VkDebugUtilsMessengerEXT> messenger_;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VulkanHandle<VkDevice> device_;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queueFamily_ = 0;
  VulkanHandle<VkCommandPool> commandPool_;
  std::unique_ptr<PipelineCache> pipelineCache_;
  std::unique_ptr<PipelineStatistics> pipelineStatistics_;
  DeviceFunctions functions_;
  DeviceInfo info_;
  Backend backend_ = Backend::Auto;
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
};

}  // namespace memograph::runtime
