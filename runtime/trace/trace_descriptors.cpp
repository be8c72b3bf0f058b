#include "runtime/trace/trace_descriptors.h"

#include <vector>

#include "runtime/shaders/shared_types.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

TraceDescriptorSet::TraceDescriptorSet(const VulkanContext& context,
                                       VkDescriptorSetLayout setLayout, const TraceResources& r) {
  VkDevice device = context.device();
  std::vector<VkDescriptorPoolSize> poolSizes = {
      {VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 2},
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 16},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, r.textures->count()}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  pool_ = VulkanHandle<VkDescriptorPool>(
      pool, [device](VkDescriptorPool p) { vkDestroyDescriptorPool(device, p, nullptr); });
  VkDescriptorSetAllocateInfo allocateInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocateInfo.descriptorPool = pool;
  allocateInfo.descriptorSetCount = 1;
  allocateInfo.pSetLayouts = &setLayout;
  checkVk(vkAllocateDescriptorSets(device, &allocateInfo, &set_), "vkAllocateDescriptorSets");
  VkDescriptorSet set = set_;

  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorBufferInfo> bufferInfos;
  bufferInfos.reserve(gpu::kBindingCount);  // the writes point into it: no reallocation
  // Each buffer is bound whole: a storage buffer must fit the device's storage-buffer range
  // (the cache's buffers were checked earlier under their options' names; this also covers
  // the scene's).
  auto writeBuffer = [&](std::uint32_t binding, VkDescriptorType type, const GpuBuffer& buffer,
                         const char* what) {
    if (type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
      checkBufferSize(context, buffer.size(), what, true);
    bufferInfos.push_back({buffer.buffer(), 0, VK_WHOLE_SIZE});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pBufferInfo = &bufferInfos.back();
    writes.push_back(write);
  };
  constexpr auto kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writeBuffer(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, *r.frame,
              "the frame constants");
  writeBuffer(gpu::kBindingAccumulation, kStorage, *r.accumulation,
              "the image being rendered (16 bytes a pixel)");
  writeBuffer(gpu::kBindingVertices, kStorage, r.scene->vertices, "the scene's vertices");
  writeBuffer(gpu::kBindingIndices, kStorage, r.scene->indices, "the scene's indices");
  writeBuffer(gpu::kBindingInstances, kStorage, r.scene->instances, "the scene's instances");
  writeBuffer(gpu::kBindingMeshes, kStorage, r.scene->meshes, "the scene's meshes");
  writeBuffer(gpu::kBindingLights, kStorage, r.scene->lights, "the scene's lights");
  writeBuffer(gpu::kBindingEnvironment, kStorage, r.scene->environment, "the environment");
  writeBuffer(gpu::kBindingRayCounter, kStorage, *r.rayCounter, "the counters");
  writeBuffer(gpu::kBindingCache, kStorage, r.cache->entries(), "the cache entries");
  writeBuffer(gpu::kBindingTileTexels, kStorage, r.cache->tileTexels(), "the tile texels");
  writeBuffer(gpu::kBindingTileLog, kStorage, r.cache->tileLog(), "the tile log");
  writeBuffer(gpu::kBindingTileQueue, kStorage, r.cache->tileQueue(), "the tile queue");
  writeBuffer(gpu::kBindingHitFeedback, kStorage, *r.hitFeedback, "the hit-feedback counters");
  if (r.pathState) {
    writeBuffer(gpu::kBindingPathState, kStorage, *r.pathState, "the wavefront's path state");
    writeBuffer(gpu::kBindingPathQueues, kStorage, *r.pathQueues, "the wavefront's path queues");
    writeBuffer(gpu::kBindingWavefrontControl, kStorage, *r.wavefrontControl,
                "the wavefront's queue counts");
  }
  VkDescriptorImageInfo tileImageInfo{VK_NULL_HANDLE, r.cache->tileImageView(),
                                      VK_IMAGE_LAYOUT_GENERAL};
  if (tileImageInfo.imageView != VK_NULL_HANDLE) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = gpu::kBindingTileImage;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    write.pImageInfo = &tileImageInfo;
    writes.push_back(write);
  }
  // The scene's TLAS, and LiPaC's counting boxes where the render has them.
  const VkAccelerationStructureKHR structures[2] = {r.tlas, r.countingBoxes};
  VkWriteDescriptorSetAccelerationStructureKHR structureInfos[2];
  const std::uint32_t structureBindings[2] = {gpu::kBindingTlas, gpu::kBindingCountingBoxes};
  for (int i = 0; i < 2; ++i) {
    if (structures[i] == VK_NULL_HANDLE)
      continue;
    structureInfos[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
    structureInfos[i].accelerationStructureCount = 1;
    structureInfos[i].pAccelerationStructures = &structures[i];
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.pNext = &structureInfos[i];
    write.dstSet = set;
    write.dstBinding = structureBindings[i];
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
    writes.push_back(write);
  }
  std::vector<VkDescriptorImageInfo> imageInfos;
  for (std::uint32_t i = 0; i < r.textures->count(); ++i)
    imageInfos.push_back(
        {r.textures->sampler(), r.textures->view(i), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  VkWriteDescriptorSet textureWrite{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  textureWrite.dstSet = set;
  textureWrite.dstBinding = gpu::kBindingTextures;
  textureWrite.descriptorCount = r.textures->count();
  textureWrite.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  textureWrite.pImageInfo = imageInfos.data();
  writes.push_back(textureWrite);
  vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

}  // namespace memograph::runtime
