// CPU-side float images: the renderer's HDR output, material textures with their mip chain,
// images the io library reads and writes, and the plain float format (PFM) the core can
// read and write without OpenImageIO.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
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

// Portable float map (PFM): "PF" (RGB) or "Pf" (grey), width height, a scale whose sign
// gives the byte order (negative: little-endian), then 32-bit floats row by row, bottom row
// first. The project's one PFM reader and writer: the core needs it on the GPU machine,
// where no image library travels, and the io library's conversions use it too.
//
// Writes RGB (alpha dropped) little-endian through files::writeFileAtomically (a unique
// temporary renamed into place), so a failure leaves no partial file. Reads "PF" and "Pf" in either
// byte order (grey fills R, G and B), alpha 1, at most 65536 pixels a side and
// files::kMaxImagePixels in all; only regular files up to files::kMaxImageFileBytes. The try* forms
// return false / nullopt with `error` saying what is wrong (without the path); the others throw
// std::runtime_error("<path>: <error>").
bool tryWritePfm(const std::filesystem::path& path, const HdrImage& image, std::string& error);
// The bytes tryWritePfm writes (for callers staging several files as one set).
std::string encodePfm(const HdrImage& image);
std::optional<HdrImage> tryReadPfm(const std::filesystem::path& path, std::string& error);
// tryReadPfm's parser on bytes in memory (the fuzz target).
std::optional<HdrImage> tryParsePfm(std::string_view bytes, std::string& error);
void writePfm(const std::filesystem::path& path, const HdrImage& image);
HdrImage readPfm(const std::filesystem::path& path);

}  // namespace memograph::runtime
