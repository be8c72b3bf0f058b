// Image means and the block-averaged mean absolute error (image_bias.h).
#include "tools/quality/image_bias.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace memograph::runtime {

BiasResult measureBias(const BiasImage& reference, const BiasImage& test, std::uint32_t block) {
  if (reference.width != test.width || reference.height != test.height || block == 0 ||
      reference.rgba.size() != std::size_t(reference.width) * reference.height * 4 ||
      test.rgba.size() != reference.rgba.size())
    throw std::invalid_argument("measureBias: images of different sizes, or block 0");
  BiasResult result;
  const std::uint32_t w = reference.width, h = reference.height;
  double blockErrorSum = 0.0;
  std::size_t blockCount = 0;
  for (std::uint32_t by = 0; by < h; by += block) {
    for (std::uint32_t bx = 0; bx < w; bx += block) {
      double r[3] = {0, 0, 0}, t[3] = {0, 0, 0};
      const std::uint32_t x1 = std::min(w, bx + block), y1 = std::min(h, by + block);
      for (std::uint32_t y = by; y < y1; ++y) {
        for (std::uint32_t x = bx; x < x1; ++x) {
          const std::size_t i = (std::size_t(y) * w + x) * 4;
          for (int c = 0; c < 3; ++c) {
            r[c] += reference.rgba[i + c];
            t[c] += test.rgba[i + c];
          }
        }
      }
      const double pixels = double(x1 - bx) * double(y1 - by);
      for (int c = 0; c < 3; ++c) {
        result.referenceMean += r[c];
        result.testMean += t[c];
        blockErrorSum += std::abs(t[c] - r[c]) / pixels;
      }
      blockCount += 3;
    }
  }
  const double samples = 3.0 * double(w) * double(h);
  result.referenceMean /= samples;
  result.testMean /= samples;
  result.blockMeanAbsoluteError = blockCount ? blockErrorSum / double(blockCount) : 0.0;
  return result;
}

}  // namespace memograph::runtime
