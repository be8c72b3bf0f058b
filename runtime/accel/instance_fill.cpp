#include "runtime/accel/instance_fill.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "runtime/shaders/shared_types.h"
#include "runtime/vk/compute_pipeline.h"

namespace memograph::runtime {

namespace {

constexpr VkBufferUsageFlags kShaderRead =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

}  // namespace

GpuInstanceFill::GpuInstanceFill(const VulkanContext& context,
                                 std::span<const VkAccelerationStructureInstanceKHR> activeRecords,
                                 std::span<const std::uint32_t> meshOfInstance,
                                 std::span<const VkAccelerationStructureInstanceKHR> boxRecords,
                                 std::uint32_t hitboxCount, std::uint32_t meshCount,
                                 const std::filesystem::path& shaderCacheDirectory)
    : instanceCount_(static_cast<std::uint32_t>(activeRecords.size())),
      hitboxCount_(boxRecords.empty() ? 0 : hitboxCount),
      meshCount_(meshCount) {
  if (meshOfInstance.size() != activeRecords.size() ||
      (!boxRecords.empty() && boxRecords.size() != activeRecords.size() + hitboxCount))
    throw std::logic_error("GpuInstanceFill: one mesh and one box per instance, one per hitbox");
  activeRecords_ = uploadBuffer(context, activeRecords, kShaderRead);
  meshOfInstance_ = uploadBuffer(context, meshOfInstance, kShaderRead);
  // Without LiPaC no box is ever kept (every state byte is Active or Inactive, no hitbox
  // byte is set), so one record's worth stands in for the templates.
  const VkAccelerationStructureInstanceKHR noBox{};
  boxRecords_ = boxRecords.empty() ? uploadBuffer(context, &noBox, sizeof noBox, kShaderRead)
                                   : uploadBuffer(context, boxRecords, kShaderRead);
  states_ =
      hostBuffer(context, (std::size_t(instanceCount_) + hitboxCount_ + 3) / 4 * 4, kShaderRead);
  meshAddresses_ = hostBuffer(
      context, std::max<std::size_t>(meshCount_, 1) * sizeof(VkDeviceAddress), kShaderRead);

  pass_ = createPushConstantPass(context, "instance_fill.comp", sizeof(gpu::InstanceFillPush),
                                 shaderCacheDirectory, "instance fill");
}

void GpuInstanceFill::upload(std::span<const std::uint8_t> states,
                             std::span<const VkDeviceAddress> meshAddresses) {
  if (states.size() != std::size_t(instanceCount_) + hitboxCount_ ||
      meshAddresses.size() != meshCount_)
    throw std::logic_error(
        "GpuInstanceFill::upload: a state per instance and hitbox, an "
        "address per mesh");
  states_.write(states.data(), states.size());
  meshAddresses_.write(meshAddresses.data(), meshAddresses.size_bytes());
}

void GpuInstanceFill::record(VkCommandBuffer commands, VkDeviceAddress records,
                             VkDeviceAddress boxRecords) const {
  gpu::InstanceFillPush push{};
  push.counts = glm::uvec4(instanceCount_, hitboxCount_, addressWords(boxRecords));
  const glm::uvec2 active = addressWords(activeRecords_.address()),
                   boxes = addressWords(boxRecords_.address());
  const glm::uvec2 meshes = addressWords(meshOfInstance_.address());
  const glm::uvec2 addresses = addressWords(meshAddresses_.address());
  const glm::uvec2 states = addressWords(states_.address()), out = addressWords(records);
  push.templates = glm::uvec4(active, boxes);
  push.sources = glm::uvec4(meshes, addresses);
  push.frame = glm::uvec4(states, out);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pass_.pipeline.get());
  vkCmdPushConstants(commands, pass_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                     &push);
  vkCmdDispatch(commands, 1, 1, 1);
  // The build reads instance records as shader reads in its own stage.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
}

}  // namespace memograph::runtime
