// What the driver says of the code it compiled for each pipeline
// (VK_KHR_pipeline_executable_properties): per executable (a compute shader, a ray-tracing
// stage) the statistics it chooses to report, such as registers, spills and instruction
// counts. Only the driver sees the machine code, so this is where a pass's register pressure
// (hence its occupancy) shows without a profiler. `bench --pipeline-statistics FILE` asks for
// it (ContextOptions::pipelineStatistics) and writes the rows as CSV.
#pragma once

#include <cstdint>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace memograph::runtime {

// One statistic of one executable of one pipeline, its value as the driver typed it (an
// integer, a float or a boolean), written as text.
struct PipelineStatistic {
  std::string pipeline;    // our name for the pipeline ("wavefront shade", ...)
  std::string executable;  // the driver's name for the executable
  std::string name;        // the driver's name for the statistic
  std::string value;
};

// The CSV header of appendPipelineStatisticsCsv's rows, with its line end.
constexpr const char* kPipelineStatisticsCsvHeader = "scene,pipeline,executable,statistic,value\n";
// One CSV line per row, in the order given, each starting with `scene`; fields with a comma
// or a quote are quoted.
void appendPipelineStatisticsCsv(std::ostream& out, const std::string& scene,
                                 const std::vector<PipelineStatistic>& rows);

// The statistics of every pipeline created with captureFlags() and then record()ed.
// Thread-safe: pipelines are created on several threads.
class PipelineStatistics {
 public:
  // `device` must have VK_KHR_pipeline_executable_properties and its pipelineExecutableInfo
  // feature enabled. Throws std::runtime_error when its entry points cannot be loaded.
  explicit PipelineStatistics(VkDevice device);

  // The create flag that makes the driver keep the statistics.
  static constexpr VkPipelineCreateFlags captureFlags() {
    return VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  }

  // Reads the statistics of `pipeline` (created with captureFlags()) under `name`. A query
  // the driver refuses is a warning on stderr, not an error: the render goes on.
  void record(VkPipeline pipeline, const std::string& name);

  // Every row so far, sorted by pipeline and executable names (pipelines are created in
  // whatever order their threads finish), each executable's statistics in the driver's order.
  std::vector<PipelineStatistic> rows() const;

 private:
  VkDevice device_;
  PFN_vkGetPipelineExecutablePropertiesKHR getProperties_ = nullptr;
  PFN_vkGetPipelineExecutableStatisticsKHR getStatistics_ = nullptr;
  mutable std::mutex mutex_;
  std::vector<PipelineStatistic> rows_;
};

}  // namespace memograph::runtime
