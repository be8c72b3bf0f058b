// Bias of a render against a reference, apart from its noise: the images' means, and the
// mean absolute difference after averaging blocks of pixels, where per-pixel noise shrinks
// with the block's size and a bias (a cache's systematic error) stays. Compared with the
// same figures for two seeds of one render, it says whether a cache's error is above noise.
#pragma once

#include <cstdint>
#include <span>

namespace memograph::runtime {

// Linear RGB images, 4 floats a pixel (alpha ignored), row by row.
struct BiasImage {
  std::span<const float> rgba;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

struct BiasResult {
  double referenceMean = 0.0;  // mean of R, G and B over every pixel
  double testMean = 0.0;
  // Mean over blocks and channels of |block mean of test - block mean of reference|; blocks
  // of block x block pixels, the last row and column of blocks cut at the image's edge.
  double blockMeanAbsoluteError = 0.0;
};

// The images must have the same size; block >= 1.
BiasResult measureBias(const BiasImage& reference, const BiasImage& test, std::uint32_t block);

}  // namespace memograph::runtime
