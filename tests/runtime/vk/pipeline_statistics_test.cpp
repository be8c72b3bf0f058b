// The driver's pipeline statistics (VK_KHR_pipeline_executable_properties): asked of a device
// without them, the context says so by name; asked of one with them (the GPU machine), every
// pipeline created records what the driver reports. The CSV quotes what needs quoting.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

#include "render_test_support.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/pipeline_statistics.h"

namespace memograph::runtime {
namespace {

TEST(PipelineStatistics, CsvQuotesFieldsWithCommasOrQuotes) {
  std::ostringstream csv;
  appendPipelineStatisticsCsv(csv, "material_scene",
                              {{"wavefront shade", "Compute Shader", "Register Count", "96"},
                               {"wavefront material Tiles, \"glazed\"", "main", "Spills", "0"}});
  EXPECT_EQ(csv.str(),
            "material_scene,wavefront shade,Compute Shader,Register Count,96\n"
            "material_scene,\"wavefront material Tiles, \"\"glazed\"\"\",main,Spills,0\n");
  EXPECT_EQ(std::string(kPipelineStatisticsCsvHeader),
            "scene,pipeline,executable,statistic,value\n");
}

TEST(PipelineStatistics, EveryPipelineRecordsTheDriversStatisticsOrTheDeviceSaysItHasNone) {
  ContextOptions options = testing::testOptions().context;
  options.pipelineStatistics = true;
  std::unique_ptr<VulkanContext> context;
  try {
    context = std::make_unique<VulkanContext>(options);
  } catch (const std::runtime_error& e) {
    // lavapipe: no such extension. The refusal names it, so the user knows what is missing.
    EXPECT_NE(std::string(e.what()).find("VK_KHR_pipeline_executable_properties"),
              std::string::npos)
        << e.what();
    return;
  }
  ASSERT_NE(context->pipelineStatistics(), nullptr);
  const PushConstantPass pass =
      createPushConstantPass(*context, "clock_warmup.comp", 16, {}, "clock warm-up");
  const auto rows = context->pipelineStatistics()->rows();
  ASSERT_FALSE(rows.empty()) << "the driver reported no statistics for a compute pipeline";
  for (const PipelineStatistic& row : rows) {
    EXPECT_EQ(row.pipeline, "clock warm-up");
    EXPECT_FALSE(row.name.empty());
    EXPECT_FALSE(row.value.empty());
  }
  EXPECT_TRUE(context->validationErrors().empty());
}

TEST(PipelineStatistics, AContextNotAskedKeepsNone) {
  VulkanContext context(testing::testOptions().context);
  EXPECT_EQ(context.pipelineStatistics(), nullptr);
}

}  // namespace
}  // namespace memograph::runtime
