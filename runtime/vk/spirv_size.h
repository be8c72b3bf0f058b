// The size of a SPIR-V module as a driver compiles it: GPU drivers (and lavapipe's LLVM)
// inline every function call, so a function called at two places is compiled twice. The
// wavefront's material passes are measured with it (docs/design/wavefront.md, "What a
// material pass holds").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace memograph::runtime {

struct SpirvSize {
  // Instructions from each OpFunction to its OpFunctionEnd, every function once.
  std::uint64_t instructions = 0;
  // The same with every call from the entry points replaced by its callee's body: what a
  // driver that inlines every call compiles.
  std::uint64_t inlinedInstructions = 0;
};

// Throws std::invalid_argument when `spirv` is not a SPIR-V module (magic number, truncated
// instruction, or a call of a function it does not define).
SpirvSize spirvSize(const std::vector<std::uint32_t>& spirv);

// The function named `name` (its OpName, without the parameter types glslang appends) in
// `spirv`, as a driver that inlines every call compiles it from the entry points: how many
// copies of it (its call sites, each counted as often as its caller is copied), and the
// inlined instructions of one copy. Both 0 when no function has that name or none calls it.
struct SpirvFunctionCopies {
  std::uint64_t copies = 0;
  std::uint64_t inlinedInstructions = 0;
};
SpirvFunctionCopies spirvFunctionCopies(const std::vector<std::uint32_t>& spirv,
                                        const std::string& name);

}  // namespace memograph::runtime
