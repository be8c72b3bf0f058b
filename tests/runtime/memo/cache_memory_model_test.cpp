// The texel cache's entry protocol (thesis §5.3.4) is written for the Vulkan memory model
// (texel_cache.glsl, cacheFence): read in the SPIR-V of the self-test's programs, which include
// the real texel_cache.glsl. Under that model a plain load or store that races with another
// invocation's store is a data race, and a fence synchronizes only through atomics, so the
// renderer's protocol may touch the cache buffer through atomics alone. lavapipe runs on x86,
// which orders plain accesses anyway: what the device does cannot show a missing atomic, the
// module can.
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/shaders/shared_types.h"
#include "tools/selftest/cache_selftest.h"

namespace memograph::runtime {
namespace {

// SPIR-V opcodes and operands read here (the SPIR-V specification, §3).
constexpr std::uint32_t kOpMemoryModel = 14, kOpConstant = 43, kOpVariable = 59, kOpLoad = 61,
                        kOpStore = 62, kOpAccessChain = 65, kOpInBoundsAccessChain = 66,
                        kOpPtrAccessChain = 67, kOpDecorate = 71, kOpMemoryBarrier = 225,
                        kOpAtomicLoad = 227, kOpAtomicStore = 228;
constexpr std::uint32_t kDecorationBinding = 33;
constexpr std::uint32_t kMemoryModelVulkan = 3;
constexpr std::uint32_t kScopeDevice = 1;
constexpr std::uint32_t kSemanticsAcquireRelease = 0x8, kSemanticsUniformMemory = 0x40,
                        kSemanticsImageMemory = 0x800, kSemanticsMakeAvailable = 0x2000,
                        kSemanticsMakeVisible = 0x4000;

struct CacheAccesses {
  std::uint32_t memoryModel = 0;
  std::uint32_t plainLoads = 0, plainStores = 0;    // through a pointer into the cache buffer
  std::uint32_t atomicLoads = 0, atomicStores = 0;  // anywhere
  std::vector<std::pair<std::uint32_t, std::uint32_t>> barriers;  // (scope, semantics)
};

CacheAccesses readCacheAccesses(const std::vector<std::uint32_t>& spirv) {
  CacheAccesses result;
  std::map<std::uint32_t, std::uint32_t> constants;  // id -> value (32-bit constants)
  std::set<std::uint32_t> cacheBindingIds;           // ids decorated Binding kBindingCache
  std::set<std::uint32_t> cachePointers;             // the variable and chains from it
  std::vector<std::pair<std::uint32_t, std::uint32_t>> barrierIds;
  for (std::size_t i = 5; i < spirv.size();) {
    const std::uint32_t opcode = spirv[i] & 0xFFFFu, count = spirv[i] >> 16;
    if (count == 0 || i + count > spirv.size())
      break;
    const std::uint32_t* op = &spirv[i];
    switch (opcode) {
      case kOpMemoryModel:
        result.memoryModel = op[2];
        break;
      case kOpConstant:
        if (count == 4)
          constants[op[2]] = op[3];
        break;
      case kOpDecorate:
        if (count >= 4 && op[2] == kDecorationBinding && op[3] == gpu::kBindingCache)
          cacheBindingIds.insert(op[1]);
        break;
      case kOpVariable:
        if (cacheBindingIds.count(op[2]))
          cachePointers.insert(op[2]);
        break;
      case kOpAccessChain:
      case kOpInBoundsAccessChain:
      case kOpPtrAccessChain:
        if (cachePointers.count(op[3]))
          cachePointers.insert(op[2]);
        break;
      case kOpLoad:
        result.plainLoads += cachePointers.count(op[3]) ? 1u : 0u;
        break;
      case kOpStore:
        result.plainStores += cachePointers.count(op[1]) ? 1u : 0u;
        break;
      case kOpAtomicLoad:
        ++result.atomicLoads;
        break;
      case kOpAtomicStore:
        ++result.atomicStores;
        break;
      case kOpMemoryBarrier:
        barrierIds.emplace_back(op[1], op[2]);
        break;
      default:
        break;
    }
    i += count;
  }
  for (const auto& [scope, semantics] : barrierIds)
    result.barriers.emplace_back(constants.at(scope), constants.at(semantics));
  return result;
}

void expectTheProtocolUsesTheMemoryModel(CacheStressMode mode, std::uint32_t storage) {
  const CacheAccesses accesses = readCacheAccesses(cacheStressSpirv(mode));
  SCOPED_TRACE(cacheStressModeName(mode));
  EXPECT_EQ(accesses.memoryModel, kMemoryModelVulkan);
  EXPECT_EQ(accesses.plainLoads, 0u) << "plain loads from the cache buffer";
  EXPECT_EQ(accesses.plainStores, 0u) << "plain stores to the cache buffer";
  EXPECT_GT(accesses.atomicLoads, 0u);
  EXPECT_GT(accesses.atomicStores, 0u);
  ASSERT_FALSE(accesses.barriers.empty());
  for (const auto& [scope, semantics] : accesses.barriers) {
    EXPECT_EQ(scope, kScopeDevice);
    EXPECT_EQ(semantics,
              kSemanticsAcquireRelease | storage | kSemanticsMakeAvailable | kSemanticsMakeVisible);
  }
}

TEST(CacheMemoryModel, TheUpdateCounterProtocolTouchesTheCacheOnlyThroughAtomics) {
  expectTheProtocolUsesTheMemoryModel(CacheStressMode::Counter, kSemanticsUniformMemory);
}

TEST(CacheMemoryModel, TheProtocolWithValuesInAnImageFencesImageMemoryToo) {
  expectTheProtocolUsesTheMemoryModel(CacheStressMode::ImageCounter,
                                      kSemanticsUniformMemory | kSemanticsImageMemory);
}

// The unprotected demonstration loads and stores the cache plainly: the reader above sees
// them, so its zero counts are not an accident of how it follows pointers.
TEST(CacheMemoryModel, TheReaderSeesThePlainAccessesOfTheUnprotectedDemonstration) {
  const CacheAccesses accesses = readCacheAccesses(cacheStressSpirv(CacheStressMode::Unprotected));
  EXPECT_GT(accesses.plainLoads, 0u);
  EXPECT_GT(accesses.plainStores, 0u);
}

}  // namespace
}  // namespace memograph::runtime
