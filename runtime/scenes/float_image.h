// An RGBA float image in memory: what the renderer's accumulation buffer reads back as,
// and what the image writers and the PFM converter take.
#pragma once

#include <cstddef>
#include <vector>

namespace memograph::runtime {

struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width*height*4, row-major, top row first, linear radiance

  float* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const float* pixel(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  }
};

}  // namespace memograph::runtime
