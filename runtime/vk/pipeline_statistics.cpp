#include "runtime/vk/pipeline_statistics.h"

#include <algorithm>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace memograph::runtime {

namespace {

std::string statisticValue(const VkPipelineExecutableStatisticKHR& statistic) {
  std::ostringstream text;
  switch (statistic.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
      text << (statistic.value.b32 ? "true" : "false");
      break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
      text << statistic.value.i64;
      break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
      text << statistic.value.u64;
      break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
      text << statistic.value.f64;
      break;
    default:
      text << "?";
  }
  return text.str();
}

void writeCsvField(std::ostream& out, const std::string& field) {
  if (field.find_first_of(",\"\n") == std::string::npos) {
    out << field;
    return;
  }
  out << '"';
  for (const char c : field) {
    if (c == '"')
      out << '"';
    out << (c == '\n' ? ' ' : c);
  }
  out << '"';
}

// Vulkan's two-call enumeration through `get(count, items)`: the count, then `items`, each
// of structure type `type`. False, after a warning naming pipeline `name`, when the driver
// refuses either call (the render goes on without that pipeline's rows).
template <typename Item, typename Get>
bool enumerate(Get get, VkStructureType type, const std::string& name, std::vector<Item>& items) {
  std::uint32_t count = 0;
  VkResult result = get(&count, nullptr);
  Item blank{};
  blank.sType = type;
  items.assign(count, blank);
  if (result == VK_SUCCESS)
    result = get(&count, items.data());
  items.resize(count);
  if (result != VK_SUCCESS)
    std::cerr << "memograph: warning: the driver gave no statistics of pipeline " << name
              << " (VkResult " << result << ")\n";
  return result == VK_SUCCESS;
}

}  // namespace

void appendPipelineStatisticsCsv(std::ostream& out, const std::string& scene,
                                 const std::vector<PipelineStatistic>& rows) {
  for (const PipelineStatistic& row : rows) {
    writeCsvField(out, scene);
    out << ',';
    writeCsvField(out, row.pipeline);
    out << ',';
    writeCsvField(out, row.executable);
    out << ',';
    writeCsvField(out, row.name);
    out << ',';
    writeCsvField(out, row.value);
    out << '\n';
  }
}

PipelineStatistics::PipelineStatistics(VkDevice device) : device_(device) {
  getProperties_ = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetDeviceProcAddr(device, "vkGetPipelineExecutablePropertiesKHR"));
  getStatistics_ = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetDeviceProcAddr(device, "vkGetPipelineExecutableStatisticsKHR"));
  if (getProperties_ == nullptr || getStatistics_ == nullptr)
    throw std::runtime_error(
        "the Vulkan driver enabled VK_KHR_pipeline_executable_properties but gave no entry "
        "points for it");
}

void PipelineStatistics::record(VkPipeline pipeline, const std::string& name) {
  VkPipelineInfoKHR pipelineInfo{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  pipelineInfo.pipeline = pipeline;
  std::vector<VkPipelineExecutablePropertiesKHR> executables;
  if (!enumerate(
          [&](std::uint32_t* count, VkPipelineExecutablePropertiesKHR* items) {
            return getProperties_(device_, &pipelineInfo, count, items);
          },
          VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR, name, executables))
    return;
  std::vector<PipelineStatistic> rows;
  for (std::uint32_t index = 0; index < executables.size(); ++index) {
    VkPipelineExecutableInfoKHR executableInfo{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    executableInfo.pipeline = pipeline;
    executableInfo.executableIndex = index;
    std::vector<VkPipelineExecutableStatisticKHR> statistics;
    if (!enumerate(
            [&](std::uint32_t* count, VkPipelineExecutableStatisticKHR* items) {
              return getStatistics_(device_, &executableInfo, count, items);
            },
            VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR, name, statistics))
      return;
    for (const auto& statistic : statistics)
      rows.push_back({name, executables[index].name, statistic.name, statisticValue(statistic)});
  }
  std::lock_guard lock(mutex_);
  rows_.insert(rows_.end(), rows.begin(), rows.end());
}

std::vector<PipelineStatistic> PipelineStatistics::rows() const {
  std::vector<PipelineStatistic> rows;
  {
    std::lock_guard lock(mutex_);
    rows = rows_;
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return std::tie(a.pipeline, a.executable) < std::tie(b.pipeline, b.executable);
  });
  return rows;
}

}  // namespace memograph::runtime
