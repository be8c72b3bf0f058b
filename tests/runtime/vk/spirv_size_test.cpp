// spirvSize and spirvFunctionCopies on modules glslang compiles here: a function called at
// two places by a function called at two places is four copies once inlined.
#include <gtest/gtest.h>

#include <stdexcept>

#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/spirv_size.h"

namespace memograph::runtime {
namespace {

// `leaf` called twice from `branch`, `branch` called CALLS times from main (-D CALLS=N).
const char* kCallGraphShader = R"(#version 460
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Values { float values[]; };
float leaf(float x) { return sin(x) * x + 1.0; }
float branch(float x) { return leaf(x) + leaf(x * 2.0); }
void main() {
  float sum = 0.0;
  for (int i = 0; i < CALLS; ++i) sum += branch(values[i]);
#if CALLS > 1
  sum += branch(values[7]);
#endif
  values[0] = sum;
}
)";

std::vector<std::uint32_t> compileCallGraph(int calls) {
  ShaderCompiler compiler({{"call_graph.comp", kCallGraphShader}}, {});
  return compiler.compile(
      {"call_graph.comp", ShaderStage::Compute, {"CALLS=" + std::to_string(calls)}});
}

TEST(SpirvSize, CountsEachCallSiteOfAFunctionAsACopyOfIt) {
  const std::vector<std::uint32_t> once = compileCallGraph(1);
  const std::vector<std::uint32_t> twice = compileCallGraph(2);
  // CALLS=1: main calls branch at one site, branch calls leaf at two.
  EXPECT_EQ(spirvFunctionCopies(once, "branch").copies, 1u);
  EXPECT_EQ(spirvFunctionCopies(once, "leaf").copies, 2u);
  // CALLS=2: a second site of branch in main doubles the copies of both.
  EXPECT_EQ(spirvFunctionCopies(twice, "branch").copies, 2u);
  EXPECT_EQ(spirvFunctionCopies(twice, "leaf").copies, 4u);
  EXPECT_EQ(spirvFunctionCopies(twice, "nowhere").copies, 0u);

  // Inlined, the module holds main's own code plus every copy of branch (each holding two of
  // leaf); written once, each function once.
  const SpirvSize size = spirvSize(twice);
  const SpirvFunctionCopies branch = spirvFunctionCopies(twice, "branch");
  const SpirvFunctionCopies leaf = spirvFunctionCopies(twice, "leaf");
  EXPECT_GT(leaf.inlinedInstructions, 0u);
  EXPECT_GT(branch.inlinedInstructions, 2 * leaf.inlinedInstructions);
  EXPECT_GT(size.inlinedInstructions, 2 * branch.inlinedInstructions);
  EXPECT_LT(size.instructions, size.inlinedInstructions);
  EXPECT_EQ(size.inlinedInstructions - spirvSize(once).inlinedInstructions,
            branch.inlinedInstructions + (size.instructions - spirvSize(once).instructions));
}

TEST(SpirvSize, RefusesWhatIsNotSpirv) {
  EXPECT_THROW(spirvSize({1u, 2u, 3u, 4u, 5u}), std::invalid_argument);
  std::vector<std::uint32_t> truncated = compileCallGraph(1);
  truncated.push_back((5u << 16) | 17u);  // an instruction of 5 words, 1 of them there
  EXPECT_THROW(spirvSize(truncated), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime
