// Concurrency stress test of the texel cache's entry protocol (thesis §5.3.4), through
// runtime::runCacheStress (tools/selftest/cache_selftest.h, also `memograph selftest`): a compute
// shader that includes the real texel_cache.glsl hammers a tiny cache (32 entries, D = 8,
// random eviction) with 64 keys whose values are a known function of the key, and checks
// every hit's values, with the values in the entry or in a storage image. A torn read is a hit
// whose values belong to another key (the A-B-A race the key-only check cannot see). The
// update-counter check must give none; the key-only count is reported, and so is an unprotected
// protocol's (no lock, no second look) to show that tears do happen here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/shaders/shared_types.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"
#include "runtime/vk/vulkan_context.h"
#include "runtime/vk/vulkan_error.h"
#include "runtime/vk/vulkan_handle.h"
#include "tools/selftest/cache_selftest.h"

namespace memograph::runtime {
namespace {

constexpr std::uint32_t kInvocations = 4096;

TEST(TexelCacheStress, UpdateCounterGivesNoTornReads) {
  testing::testOptions();  // sets XDG_RUNTIME_DIR when unset
  ContextOptions options;
  options.validation = validationLayerAvailable();
  VulkanContext context(options);
  const std::uint32_t iterations = 256;
  std::vector<CacheStressResult> results;
  for (CacheStressMode mode :
       {CacheStressMode::Key, CacheStressMode::Counter, CacheStressMode::ImageKey,
        CacheStressMode::ImageCounter, CacheStressMode::Unprotected})
    results.push_back(runCacheStress(context, mode, kInvocations, iterations));
  for (const CacheStressResult& r : results) {
    std::printf(
        "cache stress (%s, %u invocations x %u, 64 keys, %u entries): %u hits, %u misses, "
        "%u torn reads, occupancy %u\n",
        cacheStressModeName(r.mode), kInvocations, iterations, kCacheStressEntries, r.hits,
        r.misses, r.torn, r.occupancy);
    EXPECT_EQ(r.hits + r.misses, kInvocations * iterations);
    EXPECT_GT(r.hits, 0u);
    EXPECT_GT(r.misses, 0u);
    if (r.mode != CacheStressMode::Unprotected) {
      // A key never returns to empty: the occupancy counts each entry's first fill once.
      EXPECT_GT(r.occupancy, 0u);
      EXPECT_LE(r.occupancy, kCacheStressEntries);
    }
  }
  EXPECT_EQ(results[1].torn, 0u);  // counter
  EXPECT_EQ(results[3].torn, 0u);  // image-counter
  // Exactly these two fail `memograph selftest`; the others are demonstrations.
  for (const CacheStressResult& r : results)
    EXPECT_EQ(cacheStressModeMustNotTear(r.mode),
              r.mode == CacheStressMode::Counter || r.mode == CacheStressMode::ImageCounter)
        << cacheStressModeName(r.mode);
  // The unprotected protocol's tears show that the harness can see a tear on this device
  // (lavapipe: 21000 to 44000 of about 360000 hits); reported, not asserted, since it depends
  // on the device's scheduling. The key-only checks are reported too (lavapipe: 0); on the
  // GPU machine `memograph selftest` runs the same modes (docs/results.md, "Cache correctness
  // on the GPU", has its counts).
  EXPECT_TRUE(context.validationErrors().empty());
}

// §5.3.3: lrw evicts the least recently written entry even after the kept clock bits wrap.
// One invocation writes keys 1..8 into the 8 entries of one probe range with the counter
// clock (shift 0) starting 4 ticks before 2^32, so keys 5..8 are stamped 0..3 and keys
// 1..4 0xFFFFFFFC..0xFFFFFFFF; key 9 must then evict key 1, the oldest, where comparing the
// stamps themselves evicted key 5, the oldest of the wrapped ones (the newest but four).
TEST(TexelCacheStress, LrwCounterClockEvictsTheOldestAcrossTheWrap) {
  testing::testOptions();
  ContextOptions options;
  options.validation = validationLayerAvailable();
  VulkanContext context(options);
  const char* body = R"(
  if (gl_GlobalInvocationID.x != 0u) return;
  float values[MG_CACHE_VALUES];
  for (uint k = 1u; k <= 9u; ++k) {
    values[0] = float(k);
    CacheKey key;
    key.base = 0u;
    key.hash = k;
    cacheWrite(key, values);
  }
  for (uint e = 0u; e < 8u; ++e) results[e] = cacheData[cacheKeyWord(e)];
  for (uint e = 0u; e < 8u; ++e) results[8u + e] = cacheData[cacheEntryOffset(e) + kCacheClockWord];
)";
  std::vector<std::string> defines = {
      "MG_CACHE_TEXEL=1",         "MG_CACHE_VALUES=1",
      "MG_CACHE_PROBE=8",         "MG_CACHE_EVICTION=" + std::to_string(gpu::kCacheEvictionLrw),
      "MG_CACHE_CLOCK_COUNTER=1", "MG_CACHE_CLOCK_SHIFT=0"};
  std::vector<std::uint32_t> words =
      runCacheProgram(context, body, defines, 16, 64, (1ull << 32) - 4, 16);
  std::vector<std::uint32_t> keys(words.begin(), words.begin() + 8);
  std::printf("lrw across the wrap: keys");
  for (std::uint32_t e = 0; e < 8; ++e)
    std::printf(" %u@%u", words[e], words[8 + e]);
  std::printf("\n");
  EXPECT_EQ(std::count(keys.begin(), keys.end(), 1u), 0) << "the oldest entry survived";
  EXPECT_EQ(std::count(keys.begin(), keys.end(), 9u), 1);
  for (std::uint32_t k = 2; k <= 8; ++k)
    EXPECT_EQ(std::count(keys.begin(), keys.end(), k), 1) << "key " << k << " was evicted";
  EXPECT_TRUE(context.validationErrors().empty());
}

// The cone after a diffuse bounce (ray_cone.glsl, as the path tracer
// grows it). Eq. 2.11's small-angle form gave 14 rad at alpha = 1 (0.99 clamp); the bounded
// form 2 atan(sigma) equals it to first order for small alpha and is pi for a diffuse lobe.
// The LOD at the second hit: a primary cone of one pixel (alpha0 = 1 mrad) meets a wall at
// t1 = 4 and bounces diffusely to a 1 m wide texture of 256 texels at t2 = 0.05: level
// log2(w2 / 1 m * 256) with w2 = alpha0 t1 + (alpha0 + beta) t2.
TEST(RayConeSpread, DiffuseBounceIsBoundedAndTheSecondHitKeepsAFinerLevel) {
  testing::testOptions();
  ContextOptions options;
  options.validation = validationLayerAvailable();
  VulkanContext context(options);
  const char* body = R"(
  if (gl_GlobalInvocationID.x != 0u) return;
  float alphas[6] = float[](0.0, 0.05, 0.1, 0.5, 0.9, 1.0);
  for (uint i = 0u; i < 6u; ++i) results[i] = floatBitsToUint(rayConeRoughnessSpread(alphas[i]));
  RayCone cone;
  cone.width = 0.0;
  cone.spread = 0.001;
  float w1 = rayConeWidthAt(cone, 4.0);
  cone.spread = min(cone.spread + rayConeRoughnessSpread(1.0), kRayConeMaxSpread);
  cone.width = w1;
  results[6] = floatBitsToUint(rayConeWidthAt(cone, 0.05));
)";
  std::vector<std::uint32_t> words =
      runCacheProgram(context, body,
                      {"MG_CACHE_TEXEL=1", "MG_CACHE_VALUES=1", "MG_CACHE_PROBE=1",
                       "MG_CACHE_EVICTION=0", "SELFTEST_RAY_CONE=1"},
                      16, 64, 0, 7);
  auto f = [&](std::size_t i) {
    float v;
    std::memcpy(&v, &words[i], sizeof v);
    return v;
  };
  const double pi = 3.14159265358979;
  const double alphas[6] = {0.0, 0.05, 0.1, 0.5, 0.9, 1.0};
  for (int i = 0; i < 6; ++i) {
    const double a2 = std::min(alphas[i] * alphas[i], 0.99);
    const double eq211 = 2.0 * std::sqrt(a2 / (2.0 - 2.0 * a2));
    std::printf("roughness spread alpha %.2f: %.5f rad (eq. 2.11 small-angle form %.5f)\n",
                alphas[i], f(i), eq211);
    EXPECT_LE(f(i), pi + 1e-5);
    if (alphas[i] <= 0.1) {
      EXPECT_NEAR(f(i), eq211, 0.01 * eq211 + 1e-6);  // first order: the same
    }
    if (i > 0) {
      EXPECT_GT(f(i), f(i - 1));  // monotonic in roughness
    }
  }
  EXPECT_NEAR(f(5), pi, 1e-4);  // a diffuse lobe spans the hemisphere
  const double w2 = f(6);
  const double level = std::log2(w2 * 256.0);
  const double oldLevel = std::log2((0.004 + (0.001 + 14.07) * 0.05) * 256.0);
  std::printf("second hit: width %.4f m, level %.2f of 0..8 (eq. 2.11 unbounded: %.2f)\n", w2,
              level, oldLevel);
  EXPECT_NEAR(w2, 0.004 + (0.001 + pi) * 0.05, 1e-3);
  EXPECT_LT(level, oldLevel - 2.0);  // more than two levels finer than before
  EXPECT_LT(level, 8.0);             // and finer than the texture's coarsest level
  EXPECT_TRUE(context.validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
