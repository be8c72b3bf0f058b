// measureBias: block averaging removes zero-mean noise and keeps an offset; the means are the
// images' own.
#include <gtest/gtest.h>

#include <vector>

#include "tools/quality/image_bias.h"

namespace memograph::runtime {
namespace {

std::vector<float> image(std::uint32_t w, std::uint32_t h, float value) {
  std::vector<float> rgba(std::size_t(w) * h * 4, value);
  return rgba;
}

TEST(ImageBias, BlockAveragingRemovesAlternatingNoiseButKeepsAnOffset) {
  const std::uint32_t w = 16, h = 8;
  const std::vector<float> reference = image(w, h, 0.5f);
  std::vector<float> noisy = reference, offset = reference;
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        noisy[(y * w + x) * 4 + c] += ((x + y) % 2 ? 0.1f : -0.1f);
        offset[(y * w + x) * 4 + c] += 0.02f;
      }
  const BiasResult noise = measureBias({reference, w, h}, {noisy, w, h}, 8);
  EXPECT_NEAR(noise.blockMeanAbsoluteError, 0.0, 1e-6);
  EXPECT_NEAR(measureBias({reference, w, h}, {noisy, w, h}, 1).blockMeanAbsoluteError, 0.1, 1e-6);
  const BiasResult bias = measureBias({reference, w, h}, {offset, w, h}, 8);
  EXPECT_NEAR(bias.blockMeanAbsoluteError, 0.02, 1e-6);
  EXPECT_NEAR(bias.referenceMean, 0.5, 1e-6);
  EXPECT_NEAR(bias.testMean, 0.52, 1e-6);
}

TEST(ImageBias, PartialEdgeBlocksAverageTheirOwnPixels) {
  const std::uint32_t w = 5, h = 3;
  const std::vector<float> reference = image(w, h, 0.0f);
  std::vector<float> test = reference;
  test[(2 * w + 4) * 4] = 3.0f;  // the corner pixel, alone in its 4x4 block's 1x1 remainder
  const BiasResult r = measureBias({reference, w, h}, {test, w, h}, 4);
  // Blocks: 4x3 (all zero) and 1x3 (red mean 1): (0 + 1) / (2 blocks * 3 channels).
  EXPECT_NEAR(r.blockMeanAbsoluteError, 1.0 / 6.0, 1e-6);
}

TEST(ImageBias, DifferentSizesAreRefused) {
  const std::vector<float> a = image(2, 2, 0.0f), b = image(1, 4, 0.0f);
  EXPECT_THROW(measureBias({a, 2, 2}, {b, 1, 4}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime
