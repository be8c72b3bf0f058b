#include "runtime/scene/gpu_textures.h"

#include <stdexcept>

#include "runtime/vk/storage_image.h"
#include "runtime/vk/vulkan_error.h"

namespace memograph::runtime {

namespace {

constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

void transition(VkCommandBuffer commands, VkImage image, std::uint32_t levels, VkImageLayout from,
                VkImageLayout to, VkAccessFlags srcAccess, VkAccessFlags dstAccess,
                VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcAccessMask = srcAccess;
  barrier.dstAccessMask = dstAccess;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1};
  vkCmdPipelineBarrier(commands, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace

GpuTextures::GpuTextures(const VulkanContext& context, const std::vector<TextureImage>& textures) {
  VkDevice device = context.device();
  VkFormatProperties formatProperties;
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), kFormat, &formatProperties);
  if (!(formatProperties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    throw std::runtime_error(context.info().name +
                             " cannot filter RGBA32F textures linearly, which materials need");

  std::vector<TextureImage> all = textures;
  if (all.empty()) {
    HdrImage white{1, 1, {1.0f, 1.0f, 1.0f, 1.0f}};
    all.push_back(TextureImage{{white}});
  }
  for (std::size_t t = 0; t < all.size(); ++t) {
    TextureImage& texture = all[t];
    if (texture.levels.empty() || texture.levels[0].width == 0 || texture.levels[0].height == 0)
      throw std::invalid_argument("texture " + std::to_string(t) + " is empty");
    if (texture.levels.size() == 1)
      generateMipChain(texture);
    const auto levels = static_cast<std::uint32_t>(texture.levels.size());
    for (std::uint32_t l = 0; l < levels; ++l) {
      const HdrImage& level = texture.levels[l];
      std::uint32_t w = std::max(1u, texture.levels[0].width >> l);
      std::uint32_t h = std::max(1u, texture.levels[0].height >> l);
      if (level.width != w || level.height != h || level.rgba.size() != std::size_t(w) * h * 4)
        throw std::invalid_argument("texture " + std::to_string(t) + ": mip level " +
                                    std::to_string(l) + " should be " + std::to_string(w) + "x" +
                                    std::to_string(h) + " RGBA");
    }

    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = kFormat;
    info.extent = {texture.levels[0].width, texture.levels[0].height, 1};
    info.mipLevels = levels;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    checkVk(vkCreateImage(device, &info, nullptr, &image), "vkCreateImage");
    VulkanHandle<VkImage> imageOwner(image,
                                     [device](VkImage i) { vkDestroyImage(device, i, nullptr); });
    ImageMemory memory = bindDeviceLocalImageMemory(context, image, "texture");
    memories_.push_back(std::move(memory.memory));
    bytes_ += memory.bytes;

    std::size_t stagingBytes = 0;
    for (const auto& level : texture.levels)
      stagingBytes += level.rgba.size() * sizeof(float);
    GpuBuffer staging = hostBuffer(context, stagingBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::vector<VkBufferImageCopy> copies;
    std::size_t offset = 0;
    for (std::uint32_t l = 0; l < levels; ++l) {
      const HdrImage& level = texture.levels[l];
      staging.write(level.rgba.data(), level.rgba.size() * sizeof(float), offset);
      VkBufferImageCopy copy{};
      copy.bufferOffset = offset;
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
      copy.imageExtent = {level.width, level.height, 1};
      copies.push_back(copy);
      offset += level.rgba.size() * sizeof(float);
    }
    context.submitAndWait([&](VkCommandBuffer commands) {
      transition(commands, image, levels, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
      vkCmdCopyBufferToImage(commands, staging.buffer(), image,
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             static_cast<std::uint32_t>(copies.size()), copies.data());
      transition(commands, image, levels, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
    });

    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = kFormat;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    checkVk(vkCreateImageView(device, &viewInfo, nullptr, &view), "vkCreateImageView");
    images_.push_back(std::move(imageOwner));
    views_.emplace_back(view, [device](VkImageView v) { vkDestroyImageView(device, v, nullptr); });
  }

  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = VK_FILTER_LINEAR;
  samplerInfo.minFilter = VK_FILTER_LINEAR;
  samplerInfo.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  samplerInfo.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  samplerInfo.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  samplerInfo.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler = VK_NULL_HANDLE;
  checkVk(vkCreateSampler(device, &samplerInfo, nullptr, &sampler), "vkCreateSampler");
  sampler_ = VulkanHandle<VkSampler>(
      sampler, [device](VkSampler s) { vkDestroySampler(device, s, nullptr); });
}

}  // namespace memograph::runtime
