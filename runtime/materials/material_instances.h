// Material instances: distinct graphs of one shape (compiler::CompiledMaterial::shape: the
// same code but for float constants, as a recipe's materials with their own colours and
// offsets are) share one compiled wavefront material pass. The pass reads the constants that
// differ among its graphs from the bin's parameter block, and folds the others as literals
// (docs/design/wavefront.md, "Material instances"). A cold start then creates one material
// pipeline per shape, not one per graph: the driver's compile of a graph is the largest part
// of a cold start.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace memograph::runtime {

// One distinct graph, as the grouping sees it.
struct InstanceCandidate {
  // Its shape, with whatever else a shared pass needs equal (the linker adds its flags).
  std::string shape;
  std::vector<std::vector<float>> floatConstants;  // CompiledMaterial::floatConstants
};

// Graphs of one shape: `members` (indices into the candidates, ascending), the float
// constants that differ among them (by index in floatConstants: the compiler's
// CompileOptions::parameterConstants) and each member's parameter block, those constants'
// floats in index order.
struct InstanceGroup {
  std::vector<std::uint32_t> members;
  std::vector<bool> parameterConstants;
  std::uint32_t parameterCount = 0;  // floats in each member's block
  std::vector<float> parameters;     // the members' blocks, in member order
};

// Groups the candidates by shape; every candidate lands in exactly one group, the groups in
// the order of their first members (so the same scene gives the same groups).
std::vector<InstanceGroup> groupMaterialInstances(const std::vector<InstanceCandidate>& candidates);

}  // namespace memograph::runtime
