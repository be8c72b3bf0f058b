#include "runtime/materials/material_instances.h"

#include <algorithm>
#include <bit>
#include <map>

namespace memograph::runtime {
namespace {

// Bit for bit: -0 and 0 (or two NaNs) are different constants to fold.
bool sameFloats(const std::vector<float>& a, const std::vector<float>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](float x, float y) {
    return std::bit_cast<std::uint32_t>(x) == std::bit_cast<std::uint32_t>(y);
  });
}

}  // namespace

std::vector<InstanceGroup> groupMaterialInstances(
    const std::vector<InstanceCandidate>& candidates) {
  std::vector<InstanceGroup> groups;
  std::map<std::string, std::size_t> groupOfShape;
  for (std::uint32_t i = 0; i < candidates.size(); ++i) {
    const auto [known, added] = groupOfShape.emplace(candidates[i].shape, groups.size());
    if (added)
      groups.emplace_back();
    groups[known->second].members.push_back(i);
  }
  for (InstanceGroup& group : groups) {
    const auto& first = candidates[group.members.front()].floatConstants;
    group.parameterConstants.assign(first.size(), false);
    for (std::size_t c = 0; c < first.size(); ++c) {
      for (const std::uint32_t member : group.members)
        if (!sameFloats(candidates[member].floatConstants.at(c), first[c]))
          group.parameterConstants[c] = true;
      if (group.parameterConstants[c])
        group.parameterCount += static_cast<std::uint32_t>(first[c].size());
    }
    for (const std::uint32_t member : group.members) {
      const auto& constants = candidates[member].floatConstants;
      for (std::size_t c = 0; c < constants.size(); ++c)
        if (group.parameterConstants[c])
          group.parameters.insert(group.parameters.end(), constants[c].begin(), constants[c].end());
    }
  }
  return groups;
}

}  // namespace memograph::runtime
