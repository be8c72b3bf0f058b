// CPU-side float images: the renderer's HDR output, material textures with their mip chain,
// and the plain float format (PFM) the core can read and write without OpenImageIO.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace memograph::runtime {

// Linear RGBA floats, rows top to bottom.
struct HdrImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> rgba;  // width * height * 4

  float* pixel(std::uint32_t x, std::uint32_t y) { return &rgba[(y * width + x) * 4]; }
  const float* pixel(std::uint32_t x, std::uint32_t y) const { return &rgba[(y * width + x) * 4]; }
};

// A texture and its mip chain; levels[0] is the full image, each next level half the size
// (at least 1) in each dimension. An image given with one level gets its chain generated.
struct TextureImage {
  std::vector<HdrImage> levels;
};

// Box-filters level 0 down to 1x1, replacing any levels after the first.
void generateMipChain(TextureImage& texture);

// Portable float map (PF, RGB, little-endian, rows bottom to top in the file). Alpha is
// dropped on write and set to 1 on read. Errors throw std::runtime_error naming the file.
void writePfm(const std::filesystem::path& path, const HdrImage& image);
HdrImage readPfm(const std::filesystem::path& path);

}  // namespace memograph::runtime
