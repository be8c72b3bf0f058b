#include "runtime/accel/acceleration_structures.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "runtime/shaders/shared_types.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

// Makes finished builds visible to what comes next (compaction, copies, the TLAS build).
void buildBarrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR |
                          VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                       VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
}

}  // namespace

AccelerationStructure::AccelerationStructure(const VulkanContext& context,
                                             VkAccelerationStructureTypeKHR type, VkDeviceSize size)
    : buffer_(context, size,
              VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                  VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) {
  VkAccelerationStructureCreateInfoKHR info{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  info.buffer = buffer_.buffer();
  info.size = size;
  info.type = type;
  VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
  const DeviceFunctions& f = context.functions();
  checkVk(f.createAccelerationStructure(context.device(), &info, nullptr, &handle),
          "vkCreateAccelerationStructureKHR");
  VkDevice device = context.device();
  auto destroy = f.destroyAccelerationStructure;
  handle_ = VulkanHandle<VkAccelerationStructureKHR>(
      handle, [device, destroy](VkAccelerationStructureKHR h) { destroy(device, h, nullptr); });
  VkAccelerationStructureDeviceAddressInfoKHR addressInfo{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  addressInfo.accelerationStructure = handle;
  address_ = f.getAccelerationStructureDeviceAddress(device, &addressInfo);
}

VkAccelerationStructureGeometryKHR meshGeometry(const GpuBuffer& vertices,
                                                std::uint32_t vertexStride,
                                                const GpuBuffer& indices,
                                                const MeshGeometry& mesh) {
  VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  g.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  auto& t = g.geometry.triangles;
  t = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
  t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  t.vertexData.deviceAddress = vertices.address() + VkDeviceSize(mesh.firstVertex) * vertexStride;
  t.vertexStride = vertexStride;
  t.maxVertex = mesh.vertexCount - 1;
  t.indexType = VK_INDEX_TYPE_UINT32;
  t.indexData.deviceAddress = indices.address() + VkDeviceSize(mesh.firstIndex) * 4;
  return g;
}

VkAccelerationStructureBuildGeometryInfoKHR buildGeometryInfo(
    VkAccelerationStructureTypeKHR type, VkBuildAccelerationStructureFlagsKHR flags,
    VkBuildAccelerationStructureModeKHR mode, const VkAccelerationStructureGeometryKHR* geometry) {
  VkAccelerationStructureBuildGeometryInfoKHR build{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = type;
  build.flags = flags;
  build.mode = mode;
  build.geometryCount = 1;
  build.pGeometries = geometry;
  return build;
}

CompactedBlases buildCompactedBlases(const VulkanContext& context, const GpuBuffer& vertices,
                                     std::uint32_t vertexStride, const GpuBuffer& indices,
                                     std::span<const MeshGeometry> meshes) {
  CompactedBlases out;
  if (meshes.empty())
    return out;
  const DeviceFunctions& f = context.functions();
  VkDevice device = context.device();
  VkDeviceSize scratchAlignment = context.info().minAccelerationStructureScratchOffsetAlignment;

  // 1. Sizes of every BLAS, built in one batch with one scratch buffer.
  std::vector<VkAccelerationStructureGeometryKHR> geometries(meshes.size());
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> builds(meshes.size());
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges(meshes.size());
  std::vector<VkDeviceSize> scratchOffsets(meshes.size());
  std::vector<AccelerationStructure> uncompacted;
  VkDeviceSize scratchTotal = 0;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshGeometry& mesh = meshes[i];
    if (mesh.triangleCount == 0)
      throw std::runtime_error("mesh " + std::to_string(i) + " has no triangles");
    auto& g = geometries[i];
    g = meshGeometry(vertices, vertexStride, indices, mesh);
    auto& b = builds[i];
    b = buildGeometryInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                          VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                              VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR,
                          VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR, &g);
    VkAccelerationStructureBuildSizesInfoKHR sizes{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    f.getAccelerationStructureBuildSizes(device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR,
                                         &b, &mesh.triangleCount, &sizes);
    uncompacted.emplace_back(context, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                             sizes.accelerationStructureSize);
    out.bytesBeforeCompaction += sizes.accelerationStructureSize;
    out.triangles += mesh.triangleCount;
    scratchOffsets[i] = scratchTotal;
    scratchTotal = alignUp(scratchTotal + sizes.buildScratchSize, scratchAlignment);
    ranges[i] = {mesh.triangleCount, 0, 0, 0};
  }

  // 2. Build them all, then read back the compacted sizes.
  std::vector<VkDeviceSize> compactSizes(meshes.size(), 0);
  {
    GpuBuffer scratch(
        context, scratchTotal + scratchAlignment,
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    out.scratchBytes += scratch.size();
    VkDeviceAddress scratchBase = alignUp(scratch.address(), scratchAlignment);
    std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePointers;
    std::vector<VkAccelerationStructureKHR> handles;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      builds[i].dstAccelerationStructure = uncompacted[i].handle();
      builds[i].scratchData.deviceAddress = scratchBase + scratchOffsets[i];
      rangePointers.push_back(&ranges[i]);
      handles.push_back(uncompacted[i].handle());
    }
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR;
    queryInfo.queryCount = static_cast<std::uint32_t>(meshes.size());
    VkQueryPool pool = VK_NULL_HANDLE;
    checkVk(vkCreateQueryPool(device, &queryInfo, nullptr, &pool), "vkCreateQueryPool");
    VulkanHandle<VkQueryPool> poolOwner(
        pool, [device](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });
    // The builds' GPU time, between timestamps around them.
    VulkanHandle<VkQueryPool> timestampPool;
    if (context.info().timestamps) {
      VkQueryPoolCreateInfo timestampInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      timestampInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
      timestampInfo.queryCount = 2;
      VkQueryPool timestamps = VK_NULL_HANDLE;
      checkVk(vkCreateQueryPool(device, &timestampInfo, nullptr, &timestamps), "vkCreateQueryPool");
      timestampPool = VulkanHandle<VkQueryPool>(
          timestamps, [device](VkQueryPool p) { vkDestroyQueryPool(device, p, nullptr); });
    }
    context.submitAndWait([&](VkCommandBuffer commands) {
      vkCmdResetQueryPool(commands, pool, 0, queryInfo.queryCount);
      if (timestampPool) {
        vkCmdResetQueryPool(commands, timestampPool.get(), 0, 2);
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestampPool.get(), 0);
      }
      f.cmdBuildAccelerationStructures(commands, static_cast<std::uint32_t>(builds.size()),
                                       builds.data(), rangePointers.data());
      if (timestampPool)
        vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                            timestampPool.get(), 1);
      buildBarrier(commands);
      f.cmdWriteAccelerationStructuresProperties(
          commands, static_cast<std::uint32_t>(handles.size()), handles.data(),
          VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR, pool, 0);
    });
    checkVk(vkGetQueryPoolResults(device, pool, 0, queryInfo.queryCount,
                                  compactSizes.size() * sizeof(VkDeviceSize), compactSizes.data(),
                                  sizeof(VkDeviceSize),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults (compacted sizes)");
    if (timestampPool) {
      std::uint64_t ticks[2] = {0, 0};
      checkVk(vkGetQueryPoolResults(device, timestampPool.get(), 0, 2, sizeof ticks, ticks,
                                    sizeof(std::uint64_t),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults (BLAS build timestamps)");
      out.gpuMilliseconds = double(ticks[1] - ticks[0]) * context.info().timestampPeriodNs * 1e-6;
    }
  }

  // 3. Compact: copy each BLAS into a structure of its compacted size, drop the original.
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    VkDeviceSize size = compactSizes[i] ? compactSizes[i] : uncompacted[i].size();
    out.blases.emplace_back(context, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, size);
    out.bytes += size;
  }
  context.submitAndWait([&](VkCommandBuffer commands) {
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      VkCopyAccelerationStructureInfoKHR copy{
          VK_STRUCTURE_TYPE_COPY_ACCELERATION_STRUCTURE_INFO_KHR};
      copy.src = uncompacted[i].handle();
      copy.dst = out.blases[i].handle();
      copy.mode = VK_COPY_ACCELERATION_STRUCTURE_MODE_COMPACT_KHR;
      f.cmdCopyAccelerationStructure(commands, &copy);
    }
  });
  return out;
}

VkAccelerationStructureInstanceKHR instanceRecord(const glm::mat4& objectToWorld,
                                                  std::uint32_t customIndex, std::uint32_t mask,
                                                  VkDeviceAddress blas) {
  if (customIndex >= (1u << 24))
    throw std::runtime_error("more than 2^24 instances and counting boxes");
  VkAccelerationStructureInstanceKHR record{};
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 4; ++column)
      record.transform.matrix[row][column] = objectToWorld[column][row];
  record.instanceCustomIndex = customIndex;
  record.mask = mask;
  record.instanceShaderBindingTableRecordOffset = 0;
  record.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
  record.accelerationStructureReference = blas;
  return record;
}

namespace {

VkAccelerationStructureBuildGeometryInfoKHR tlasBuildInfo(
    const VkAccelerationStructureGeometryKHR* geometry) {
  return buildGeometryInfo(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                           VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
                           VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR, geometry);
}

VkAccelerationStructureGeometryKHR tlasGeometry(VkDeviceAddress records) {
  VkAccelerationStructureGeometryKHR geometry{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geometry.geometry.instances = {
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
  geometry.geometry.instances.data.deviceAddress = records;
  return geometry;
}

}  // namespace

TopLevelStructure::TopLevelStructure(const VulkanContext& context, std::uint32_t capacity)
    : context_(&context), capacity_(std::max(capacity, 1u)) {
  const VkDeviceSize recordBytes = sizeof(VkAccelerationStructureInstanceKHR) * capacity_;
  instances_ = hostBuffer(context, recordBytes, kAccelerationBuildInput);
  VkAccelerationStructureGeometryKHR geometry = tlasGeometry(instances_.address());
  VkAccelerationStructureBuildGeometryInfoKHR build = tlasBuildInfo(&geometry);
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  context.functions().getAccelerationStructureBuildSizes(
      context.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &capacity_,
      &sizes);
  tlas_ = AccelerationStructure(context, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                                sizes.accelerationStructureSize);
  VkDeviceSize scratchAlignment = context.info().minAccelerationStructureScratchOffsetAlignment;
  scratch_ =
      GpuBuffer(context, sizes.buildScratchSize + scratchAlignment,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
}

VkAccelerationStructureInstanceKHR* TopLevelStructure::records() const {
  return static_cast<VkAccelerationStructureInstanceKHR*>(instances_.mapped());
}

void TopLevelStructure::recordBuild(VkCommandBuffer commands, std::uint32_t count) const {
  if (count > capacity_)
    throw std::logic_error("TopLevelStructure: " + std::to_string(count) + " records for " +
                           std::to_string(capacity_));
  VkAccelerationStructureGeometryKHR geometry = tlasGeometry(instances_.address());
  VkAccelerationStructureBuildGeometryInfoKHR build = tlasBuildInfo(&geometry);
  build.dstAccelerationStructure = tlas_.handle();
  VkDeviceSize scratchAlignment = context_->info().minAccelerationStructureScratchOffsetAlignment;
  build.scratchData.deviceAddress = alignUp(scratch_.address(), scratchAlignment);
  VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* rangePointer = &range;
  context_->functions().cmdBuildAccelerationStructures(commands, 1, &build, &rangePointer);
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

SceneAccelerationStructures::SceneAccelerationStructures(
    const VulkanContext& context, const GpuBuffer& vertices, std::uint32_t vertexStride,
    const GpuBuffer& indices, const std::vector<MeshGeometry>& meshes,
    const std::vector<InstancePlacement>& instances) {
  auto start = std::chrono::steady_clock::now();
  CompactedBlases built = buildCompactedBlases(context, vertices, vertexStride, indices, meshes);
  blases_ = std::move(built.blases);
  stats_.blasCount = static_cast<std::uint32_t>(blases_.size());
  stats_.blasBytes = built.bytes;
  stats_.blasBytesBeforeCompaction = built.bytesBeforeCompaction;
  stats_.scratchBytes = built.scratchBytes;

  // The TLAS: one instance record per scene instance; the custom index finds the instance's
  // data in the shaders.
  if (instances.size() >= (1u << 24))
    throw std::runtime_error("more than 2^24 instances");
  tlas_ =
      std::make_unique<TopLevelStructure>(context, static_cast<std::uint32_t>(instances.size()));
  VkAccelerationStructureInstanceKHR* records = tlas_->records();
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const InstancePlacement& placement = instances[i];
    if (placement.mesh >= blases_.size())
      throw std::runtime_error("instance " + std::to_string(i) + " names mesh " +
                               std::to_string(placement.mesh) + ", but the scene has " +
                               std::to_string(blases_.size()) + " meshes");
    records[i] = instanceRecord(placement.objectToWorld, static_cast<std::uint32_t>(i),
                                placement.castsShadow ? gpu::kMaskSurface : gpu::kMaskLightQuad,
                                blases_[placement.mesh].address());
  }
  auto instanceCount = static_cast<std::uint32_t>(instances.size());
  context.submitAndWait(
      [&](VkCommandBuffer commands) { tlas_->recordBuild(commands, instanceCount); });
  stats_.tlasBytes = tlas_->bytes();
  stats_.scratchBytes += tlas_->scratchBytes();
  stats_.instanceCount = instanceCount;
  stats_.buildMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace memograph::runtime
