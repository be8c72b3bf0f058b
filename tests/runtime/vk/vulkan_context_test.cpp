// The context tests switch validation on when the layer is installed; this pins down that
// a validation error then really reaches validationErrors(), so the image tests' "no
// validation errors" checks can fail.
#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {
namespace {

TEST(VulkanContext, PicksARayTracingDeviceAndNamesIt) {
  VulkanContext context(testing::testOptions().context);
  EXPECT_FALSE(context.info().name.empty());
  EXPECT_TRUE(context.info().rayQuery || context.info().rayTracingPipeline);
  EXPECT_NE(context.backend(), Backend::Auto);
  std::printf("device: %s, backend %s, validation %s\n", context.info().name.c_str(),
              backendName(context.backend()), validationLayerAvailable() ? "on" : "absent");
}

TEST(VulkanContext, AutoBackendPrefersQueryUnlessToldToPreferThePipeline) {
  ContextOptions options = testing::testOptions().context;
  options.backend = Backend::Auto;
  VulkanContext plain(options);
  if (!plain.info().rayQuery || !plain.info().rayTracingPipeline)
    GTEST_SKIP() << "the device lacks one of the two backends";
  EXPECT_EQ(plain.backend(), Backend::RayQuery);
  options.autoPrefersPipeline = true;
  VulkanContext manyMaterials(options);
  EXPECT_EQ(manyMaterials.backend(), Backend::RayTracingPipeline);
}

TEST(VulkanContext, ValidationErrorsAreCaught) {
  if (!validationLayerAvailable())
    GTEST_SKIP() << "VK_LAYER_KHRONOS_validation not installed";
  VulkanContext context(testing::testOptions().context);
  ASSERT_TRUE(context.validationErrors().empty());
  // A zero-sized buffer breaks VUID-VkBufferCreateInfo-size-00912.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  vkCreateBuffer(context.device(), &info, nullptr, &buffer);
  if (buffer != VK_NULL_HANDLE)
    vkDestroyBuffer(context.device(), buffer, nullptr);
  EXPECT_FALSE(context.validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
