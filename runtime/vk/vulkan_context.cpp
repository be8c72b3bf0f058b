#include "runtime/vk/vulkan_context.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return extensions;
}

bool hasExtension(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

struct Candidate {
  VkPhysicalDevice device = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  bool accelerationStructure = false;
  bool rayQuery = false;
  bool rayTracingPipeline = false;
  bool pipelineCreationFeedback = false;
  bool pipelineExecutableProperties = false;
  std::vector<std::string> missing;  // what keeps it from ray tracing
};

Candidate inspect(VkPhysicalDevice device) {
  Candidate c;
  c.device = device;
  vkGetPhysicalDeviceProperties(device, &c.properties);
  auto extensions = deviceExtensions(device);
  c.accelerationStructure =
      hasExtension(extensions, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
      hasExtension(extensions, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
  c.rayQuery = c.accelerationStructure && hasExtension(extensions, VK_KHR_RAY_QUERY_EXTENSION_NAME);
  c.rayTracingPipeline = c.accelerationStructure &&
                         hasExtension(extensions, VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
  c.pipelineCreationFeedback =
      hasExtension(extensions, VK_EXT_PIPELINE_CREATION_FEEDBACK_EXTENSION_NAME);
  c.pipelineExecutableProperties =
      hasExtension(extensions, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
  if (c.properties.apiVersion < VK_API_VERSION_1_2)
    c.missing.push_back("Vulkan 1.2");
  if (!c.accelerationStructure)
    c.missing.push_back(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
  if (!c.rayQuery && !c.rayTracingPipeline) {
    c.missing.push_back(std::string(VK_KHR_RAY_QUERY_EXTENSION_NAME) + " or " +
                        VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
  }
  return c;
}

const char* typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::string describe(std::size_t index, const Candidate& c) {
  // Appended: GCC 12 warns falsely (-Wrestrict) on "[" + std::to_string(index).
  std::string text = "[";
  text += std::to_string(index) + "] " + c.properties.deviceName + " (" +
          typeName(c.properties.deviceType) + "): ";
  if (c.missing.empty()) {
    text += std::string(c.rayQuery ? "ray query" : "") +
            (c.rayQuery && c.rayTracingPipeline ? ", " : "") +
            (c.rayTracingPipeline ? "ray-tracing pipeline" : "");
  } else {
    text += "no ray tracing (lacks";
    for (const auto& m : c.missing)
      text += " " + m;
    text += ")";
  }
  return text;
}

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

VkInstance createInstance(bool validation, bool withDebugUtils) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "memograph";
  app.apiVersion = VK_API_VERSION_1_2;
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (validation)
    layers.push_back(kValidationLayer);
  if (withDebugUtils)
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw VulkanError(
        "No Vulkan driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER). Install one "
        "(on Debian: mesa-vulkan-drivers from bookworm-backports, see tools/setup.sh) or set "
        "VK_DRIVER_FILES to the driver's ICD json.",
        result);
  }
  checkVk(result, "vkCreateInstance");
  return instance;
}

bool instanceLayerPresent(const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

// Loads device entry point `name` into `function` (its PFN type deduced from the field).
template <typename T>
void loadDevice(VkDevice device, const char* name, T& function) {
  function = reinterpret_cast<T>(vkGetDeviceProcAddr(device, name));
  if (!function)
    throw std::runtime_error(std::string("Vulkan entry point missing: ") + name);
}

}  // namespace

const char* backendName(Backend backend) {
  switch (backend) {
    case Backend::Auto:
      return "auto";
    case Backend::RayQuery:
      return "query";
    case Backend::RayTracingPipeline:
      return "pipeline";
  }
  return "?";
}

Backend parseBackend(const std::string& text) {
  if (text == "auto")
    return Backend::Auto;
  if (text == "query")
    return Backend::RayQuery;
  if (text == "pipeline")
    return Backend::RayTracingPipeline;
  throw std::invalid_argument("unknown backend '" + text +
                              "': choose auto, query (compute + VK_KHR_ray_query) or pipeline "
                              "(VK_KHR_ray_tracing_pipeline)");
}

struct ValidationLog {
  std::mutex mutex;
  std::vector<std::string> errors;
};

namespace {
VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    auto* log = static_cast<ValidationLog*>(user);
    std::lock_guard lock(log->mutex);
    log->errors.push_back(data->pMessage ? data->pMessage : "(no message)");
  }
  return VK_FALSE;
}
}  // namespace

bool validationLayerAvailable() {
  return instanceLayerPresent(kValidationLayer);
}

std::vector<std::string> describeDevices() {
  VulkanHandle<VkInstance> instance(createInstance(false, false),
                                    [](VkInstance i) { vkDestroyInstance(i, nullptr); });
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance.get(), &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance.get(), &count, devices.data());
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < devices.size(); ++i)
    lines.push_back(describe(i, inspect(devices[i])));
  return lines;
}

namespace {

// The debug messenger that collects validation errors into `log`.
VulkanHandle<VkDebugUtilsMessengerEXT> createMessenger(VkInstance instance, ValidationLog* log) {
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = onValidationMessage;
  info.pUserData = log;  // the context's first member, so it outlives the messenger
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkResult result = create(instance, &info, nullptr, &messenger);
  checkVk(result, "vkCreateDebugUtilsMessengerEXT");
  return VulkanHandle<VkDebugUtilsMessengerEXT>(
      messenger,
      [instance, destroy](VkDebugUtilsMessengerEXT m) { destroy(instance, m, nullptr); });
}

// The device --device names, else the best-ranked one that ray traces with the backend asked
// for; throws listing the devices when there is none.
Candidate chooseDevice(VkInstance instance, const ContextOptions& options) {
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  if (devices.empty()) {
    throw std::runtime_error(
        "No Vulkan device found. Install a driver (on Debian: mesa-vulkan-drivers from "
        "bookworm-backports for lavapipe, see tools/setup.sh).");
  }
  std::vector<Candidate> candidates;
  for (auto d : devices)
    candidates.push_back(inspect(d));
  std::string listing;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    listing += "\n  " + describe(i, candidates[i]);

  auto supportsBackend = [&](const Candidate& c) {
    if (!c.missing.empty())
      return false;
    if (options.backend == Backend::RayQuery)
      return c.rayQuery;
    if (options.backend == Backend::RayTracingPipeline)
      return c.rayTracingPipeline;
    return true;
  };
  const Candidate* chosen = nullptr;
  if (options.deviceIndex >= 0) {
    if (static_cast<std::size_t>(options.deviceIndex) >= candidates.size()) {
      throw std::runtime_error("--device " + std::to_string(options.deviceIndex) +
                               " is out of range; the devices are:" + listing);
    }
    chosen = &candidates[options.deviceIndex];
    if (!chosen->missing.empty()) {
      throw std::runtime_error("Device " + describe(options.deviceIndex, *chosen) +
                               " cannot ray trace. The devices are:" + listing);
    }
  } else {
    for (const auto& c : candidates) {
      if (!supportsBackend(c))
        continue;
      if (!chosen || typeRank(c.properties.deviceType) < typeRank(chosen->properties.deviceType))
        chosen = &c;
    }
    if (!chosen) {
      throw std::runtime_error(
          std::string("No Vulkan device supports ray tracing") +
          (options.backend == Backend::Auto
               ? ""
               : std::string(" with the ") + backendName(options.backend) + " backend") +
          ". The devices are:" + listing +
          "\nOn Debian 12, lavapipe gets ray tracing from Mesa in bookworm-backports "
          "(tools/setup.sh installs it).");
    }
  }
  return *chosen;
}

// The backend Auto resolves to on `chosen`; throws where the one asked for is missing.
Backend chooseBackend(const ContextOptions& options, const Candidate& chosen) {
  Backend backend = options.backend;
  if (backend == Backend::Auto) {
    const bool pipeline =
        !chosen.rayQuery || (options.autoPrefersPipeline && chosen.rayTracingPipeline);
    backend = pipeline ? Backend::RayTracingPipeline : Backend::RayQuery;
  }
  if (backend == Backend::RayQuery && !chosen.rayQuery) {
    throw std::runtime_error(std::string("The query backend needs VK_KHR_ray_query, which ") +
                             chosen.properties.deviceName +
                             " does not expose; use --backend pipeline (or auto).");
  }
  if (backend == Backend::RayTracingPipeline && !chosen.rayTracingPipeline) {
    throw std::runtime_error(std::string("The pipeline backend needs VK_KHR_ray_tracing_pipeline, "
                                         "which ") +
                             chosen.properties.deviceName +
                             " does not expose; use --backend query (or auto).");
  }
  return backend;
}

// The features the renderer needs, checked (throws naming what is missing) and read.
struct SupportedFeatures {
  VkPhysicalDeviceRayQueryFeaturesKHR rayQueryFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR pipelineFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR asFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceVulkan12Features features12{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
};

void readFeatures(VkPhysicalDevice physicalDevice, Backend backend, const std::string& name,
                  SupportedFeatures& supported) {
  auto& [rayQueryFeatures, pipelineFeatures, asFeatures, features12, features2] = supported;
  features2.pNext = &features12;
  features12.pNext = &asFeatures;
  asFeatures.pNext = backend == Backend::RayQuery ? static_cast<void*>(&rayQueryFeatures)
                                                  : static_cast<void*>(&pipelineFeatures);
  vkGetPhysicalDeviceFeatures2(physicalDevice, &features2);
  std::vector<std::string> missingFeatures;
  if (!features12.bufferDeviceAddress)
    missingFeatures.push_back("bufferDeviceAddress");
  if (!features12.shaderSampledImageArrayNonUniformIndexing)
    missingFeatures.push_back("shaderSampledImageArrayNonUniformIndexing");
  // The material cache's protocol is written for the Vulkan memory model with device-scope
  // atomics and fences (texel_cache.glsl, cacheFence); shaders that include it declare it.
  if (!features12.vulkanMemoryModel)
    missingFeatures.push_back("vulkanMemoryModel");
  if (!features12.vulkanMemoryModelDeviceScope)
    missingFeatures.push_back("vulkanMemoryModelDeviceScope");
  if (!asFeatures.accelerationStructure)
    missingFeatures.push_back("accelerationStructure");
  if (backend == Backend::RayQuery && !rayQueryFeatures.rayQuery)
    missingFeatures.push_back("rayQuery");
  if (backend == Backend::RayTracingPipeline && !pipelineFeatures.rayTracingPipeline)
    missingFeatures.push_back("rayTracingPipeline");
  if (!missingFeatures.empty()) {
    std::string names;
    for (const auto& f : missingFeatures)
      names += " " + f;
    throw std::runtime_error(name + " lacks Vulkan features the renderer needs:" + names);
  }
}

// Exactly the features used, chained from `enable2`; the optional ones recorded in `info`.
struct EnabledFeatures {
  VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR enableAs{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR enableQuery{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR enablePipeline{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  VkPhysicalDeviceFeatures2 enable2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
};

void enableFeatures(const SupportedFeatures& supported, Backend backend, DeviceInfo& info,
                    EnabledFeatures& e) {
  const auto& [rayQueryFeatures, pipelineFeatures, asFeatures, features12, features2] = supported;
  auto& [enable12, enableAs, enableQuery, enablePipeline, enable2] = e;
  enable12.bufferDeviceAddress = VK_TRUE;
  enable12.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
  enable12.hostQueryReset = features12.hostQueryReset;
  enable12.vulkanMemoryModel = VK_TRUE;
  enable12.vulkanMemoryModelDeviceScope = VK_TRUE;
  // Optional: only the counter clock uses them, and the renderer names them if missing.
  info.bufferInt64Atomics = features2.features.shaderInt64 && features12.shaderBufferInt64Atomics;
  enable12.shaderBufferInt64Atomics = info.bufferInt64Atomics;
  enableAs.accelerationStructure = VK_TRUE;
  enableQuery.rayQuery = VK_TRUE;
  enablePipeline.rayTracingPipeline = VK_TRUE;
  // Optional: only the wavefront path tracer's indirect launches use it.
  info.traceRaysIndirect = backend == Backend::RayTracingPipeline &&
                           pipelineFeatures.rayTracingPipelineTraceRaysIndirect;
  enablePipeline.rayTracingPipelineTraceRaysIndirect = info.traceRaysIndirect;
  enable2.features.shaderInt64 = info.bufferInt64Atomics;
  enable2.pNext = &enable12;
  enable12.pNext = &enableAs;
  enableAs.pNext = backend == Backend::RayQuery ? static_cast<void*>(&enableQuery)
                                                : static_cast<void*>(&enablePipeline);
}

// A queue family with compute (ray tracing runs on compute queues too); records whether it
// has timestamps.
std::uint32_t chooseQueueFamily(VkPhysicalDevice physicalDevice, DeviceInfo& info) {
  std::uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
  bool found = false;
  std::uint32_t queueFamily = 0;
  for (std::uint32_t i = 0; i < familyCount; ++i) {
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
      queueFamily = i;
      found = true;
      info.timestamps = families[i].timestampValidBits > 0;
      break;
    }
  }
  if (!found)
    throw std::runtime_error(info.name + " has no compute queue");
  return queueFamily;
}

void loadDeviceFunctions(VkDevice device, Backend backend, bool traceRaysIndirect,
                         DeviceFunctions& functions) {
  loadDevice(device, "vkCreateAccelerationStructureKHR", functions.createAccelerationStructure);
  loadDevice(device, "vkDestroyAccelerationStructureKHR", functions.destroyAccelerationStructure);
  loadDevice(device, "vkGetAccelerationStructureBuildSizesKHR",
             functions.getAccelerationStructureBuildSizes);
  loadDevice(device, "vkCmdBuildAccelerationStructuresKHR",
             functions.cmdBuildAccelerationStructures);
  loadDevice(device, "vkCmdCopyAccelerationStructureKHR", functions.cmdCopyAccelerationStructure);
  loadDevice(device, "vkCmdWriteAccelerationStructuresPropertiesKHR",
             functions.cmdWriteAccelerationStructuresProperties);
  loadDevice(device, "vkGetAccelerationStructureDeviceAddressKHR",
             functions.getAccelerationStructureDeviceAddress);
  if (backend == Backend::RayTracingPipeline) {
    loadDevice(device, "vkCreateRayTracingPipelinesKHR", functions.createRayTracingPipelines);
    loadDevice(device, "vkGetRayTracingShaderGroupHandlesKHR",
               functions.getRayTracingShaderGroupHandles);
    loadDevice(device, "vkCmdTraceRaysKHR", functions.cmdTraceRays);
    if (traceRaysIndirect)
      loadDevice(device, "vkCmdTraceRaysIndirectKHR", functions.cmdTraceRaysIndirect);
    loadDevice(device, "vkGetRayTracingShaderGroupStackSizeKHR",
               functions.getRayTracingShaderGroupStackSize);
    loadDevice(device, "vkCmdSetRayTracingPipelineStackSizeKHR",
               functions.cmdSetRayTracingPipelineStackSize);
    loadDevice(device, "vkCreateDeferredOperationKHR", functions.createDeferredOperation);
    loadDevice(device, "vkDestroyDeferredOperationKHR", functions.destroyDeferredOperation);
    loadDevice(device, "vkGetDeferredOperationMaxConcurrencyKHR",
               functions.getDeferredOperationMaxConcurrency);
    loadDevice(device, "vkGetDeferredOperationResultKHR", functions.getDeferredOperationResult);
    loadDevice(device, "vkDeferredOperationJoinKHR", functions.deferredOperationJoin);
  }
}

// The limits and properties the renderer sizes its work by.
void readProperties(VkPhysicalDevice physicalDevice, DeviceInfo& info) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR asProperties{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  info.rayTracingProperties.sType =
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR;
  asProperties.pNext = &info.rayTracingProperties;
  VkPhysicalDeviceSubgroupProperties subgroupProperties{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  info.rayTracingProperties.pNext = &subgroupProperties;
  VkPhysicalDeviceMaintenance3Properties maintenance3{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  subgroupProperties.pNext = &maintenance3;
  VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties2.pNext = &asProperties;
  vkGetPhysicalDeviceProperties2(physicalDevice, &properties2);
  info.rayTracingProperties.pNext = nullptr;
  info.subgroupSize = subgroupProperties.subgroupSize;
  info.subgroupOperations = subgroupProperties.supportedOperations;
  info.subgroupStages = subgroupProperties.supportedStages;
  info.limits = properties2.properties.limits;
  info.maxMemoryAllocationSize = maintenance3.maxMemoryAllocationSize;
  constexpr VkSubgroupFeatureFlags kNeeded =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  if ((subgroupProperties.supportedOperations & kNeeded) == kNeeded)
    info.subgroupArithmeticStages = subgroupProperties.supportedStages;
  info.minAccelerationStructureScratchOffsetAlignment =
      std::max(1u, asProperties.minAccelerationStructureScratchOffsetAlignment);
}

}  // namespace

namespace {

// What a device's properties say of it, before its features or limits are read.
DeviceInfo describeCandidate(const Candidate& chosen) {
  DeviceInfo info;
  info.name = chosen.properties.deviceName;
  info.type = chosen.properties.deviceType;
  info.apiVersion = chosen.properties.apiVersion;
  info.rayQuery = chosen.rayQuery;
  info.rayTracingPipeline = chosen.rayTracingPipeline;
  info.timestampPeriodNs = chosen.properties.limits.timestampPeriod;
  return info;
}

}  // namespace

std::optional<DeviceInfo> peekDeviceInfo(const ContextOptions& options) {
  try {
    VulkanHandle<VkInstance> instance(createInstance(false, false),
                                      [](VkInstance i) { vkDestroyInstance(i, nullptr); });
    const Candidate chosen = chooseDevice(instance.get(), options);
    DeviceInfo info = describeCandidate(chosen);
    readProperties(chosen.device, info);
    return info;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

VulkanContext::VulkanContext(const ContextOptions& options)
    : validationLog_(std::make_unique<ValidationLog>()) {
  if (options.validation && !instanceLayerPresent(kValidationLayer)) {
    throw std::runtime_error(
        "Validation was asked for but VK_LAYER_KHRONOS_validation is not installed (Debian: "
        "vulkan-validationlayers).");
  }
  instance_ = VulkanHandle<VkInstance>(createInstance(options.validation, options.validation),
                                       [](VkInstance i) { vkDestroyInstance(i, nullptr); });
  if (options.validation)
    messenger_ = createMessenger(instance_.get(), validationLog_.get());

  const Candidate chosen = chooseDevice(instance_.get(), options);
  physicalDevice_ = chosen.device;
  backend_ = chooseBackend(options, chosen);
  info_ = describeCandidate(chosen);

  // Features: check what the renderer needs before asking for it, to name what is missing.
  SupportedFeatures supported;
  readFeatures(physicalDevice_, backend_, info_.name, supported);
  EnabledFeatures enabled;
  enableFeatures(supported, backend_, info_, enabled);

  std::vector<const char*> extensions = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                         VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  extensions.push_back(backend_ == Backend::RayQuery ? VK_KHR_RAY_QUERY_EXTENSION_NAME
                                                     : VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
  // Optional: only the pipeline cache's counts of hits use it.
  info_.pipelineCreationFeedback = chosen.pipelineCreationFeedback;
  if (info_.pipelineCreationFeedback)
    extensions.push_back(VK_EXT_PIPELINE_CREATION_FEEDBACK_EXTENSION_NAME);
  // Only when asked: capturing statistics may cost the driver time at every creation.
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR enableExecutableInfo{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  if (options.pipelineStatistics) {
    if (!chosen.pipelineExecutableProperties)
      throw std::runtime_error("The Vulkan driver of " + info_.name +
                               " does not report pipeline statistics (it lacks " +
                               VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME + ").");
    extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    enableExecutableInfo.pipelineExecutableInfo = VK_TRUE;
    enableExecutableInfo.pNext = enabled.enable2.pNext;
    enabled.enable2.pNext = &enableExecutableInfo;
  }

  queueFamily_ = chooseQueueFamily(physicalDevice_, info_);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &enabled.enable2;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  deviceInfo.ppEnabledExtensionNames = extensions.data();
  VkDevice device = VK_NULL_HANDLE;
  checkVk(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device), "vkCreateDevice");
  device_ = VulkanHandle<VkDevice>(device, [](VkDevice d) {
    vkDeviceWaitIdle(d);
    vkDestroyDevice(d, nullptr);
  });
  vkGetDeviceQueue(device, queueFamily_, 0, &queue_);
  if (options.pipelineStatistics)
    pipelineStatistics_ = std::make_unique<PipelineStatistics>(device);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VkCommandPool pool = VK_NULL_HANDLE;
  checkVk(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
  commandPool_ = VulkanHandle<VkCommandPool>(
      pool, [device](VkCommandPool p) { vkDestroyCommandPool(device, p, nullptr); });

  loadDeviceFunctions(device, backend_, info_.traceRaysIndirect, functions_);
  readProperties(physicalDevice_, info_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
  pipelineCache_ = std::make_unique<PipelineCache>(
      device, chosen.properties,
      options.pipelineCacheDirectory.empty()
          ? std::filesystem::path()
          : options.pipelineCacheDirectory / pipelineCacheFileName(chosen.properties));
}

VulkanContext::~VulkanContext() {
  // Members go in reverse order: pool, pipeline cache, device, messenger, instance.
  commandPool_.reset();
  pipelineCache_.reset();
  pipelineStatistics_.reset();
  device_.reset();
}

std::vector<std::string> VulkanContext::validationErrors() const {
  std::lock_guard lock(validationLog_->mutex);
  return validationLog_->errors;
}

std::uint32_t VulkanContext::findMemoryType(std::uint32_t typeBits,
                                            VkMemoryPropertyFlags properties) const {
  for (std::uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    if ((typeBits & (1u << i)) &&
        (memoryProperties_.memoryTypes[i].propertyFlags & properties) == properties)
      return i;
  }
  throw VulkanError("No memory type with the needed properties", VK_ERROR_OUT_OF_DEVICE_MEMORY);
}

VkCommandBuffer VulkanContext::beginOneTimeCommands() const {
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = commandPool_.get();
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  checkVk(vkAllocateCommandBuffers(device(), &info, &commands), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  checkVk(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  return commands;
}

void VulkanContext::endOneTimeCommands(VkCommandBuffer commands) const {
  VkCommandPool pool = commandPool_.get();
  VkDevice dev = device();
  VulkanHandle<VkCommandBuffer> owner(
      commands, [dev, pool](VkCommandBuffer c) { vkFreeCommandBuffers(dev, pool, 1, &c); });
  checkVk(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  checkVk(vkCreateFence(dev, &fenceInfo, nullptr, &fence), "vkCreateFence");
  VulkanHandle<VkFence> fenceOwner(fence, [dev](VkFence f) { vkDestroyFence(dev, f, nullptr); });
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  checkVk(vkQueueSubmit(queue_, 1, &submit, fence), "vkQueueSubmit");
  checkVk(vkWaitForFences(dev, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

}  // namespace memograph::runtime
