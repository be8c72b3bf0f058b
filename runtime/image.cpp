#include "runtime/image.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace memograph::runtime {

void generateMipChain(TextureImage& texture) {
  if (texture.levels.empty())
    throw std::invalid_argument("texture without image");
  texture.levels.resize(1);
  while (texture.levels.back().width > 1 || texture.levels.back().height > 1) {
    const HdrImage& src = texture.levels.back();
    HdrImage dst;
    dst.width = std::max(1u, src.width / 2);
    dst.height = std::max(1u, src.height / 2);
    dst.rgba.assign(std::size_t(dst.width) * dst.height * 4, 0.0f);
    for (std::uint32_t y = 0; y < dst.height; ++y) {
      for (std::uint32_t x = 0; x < dst.width; ++x) {
        float* out = dst.pixel(x, y);
        int n = 0;
        for (std::uint32_t dy = 0; dy < 2; ++dy) {
          for (std::uint32_t dx = 0; dx < 2; ++dx) {
            std::uint32_t sx = std::min(src.width - 1, 2 * x + dx);
            std::uint32_t sy = std::min(src.height - 1, 2 * y + dy);
            const float* in = src.pixel(sx, sy);
            for (int c = 0; c < 4; ++c)
              out[c] += in[c];
            ++n;
          }
        }
        for (int c = 0; c < 4; ++c)
          out[c] /= float(n);
      }
    }
    texture.levels.push_back(std::move(dst));
  }
}

namespace {

std::uint32_t byteSwap(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

void swapFloats(std::vector<float>& values) {
  for (float& f : values)
    f = std::bit_cast<float>(byteSwap(std::bit_cast<std::uint32_t>(f)));
}

constexpr long long kMaxPfmSide = 65536;

}  // namespace

bool tryWritePfm(const std::filesystem::path& path, const HdrImage& image, std::string& error) {
  if (image.width == 0 || image.height == 0 ||
      image.rgba.size() != std::size_t(image.width) * image.height * 4) {
    error = "cannot write PFM: the image is empty or its size does not match";
    return false;
  }
  std::filesystem::path temporary = path;
  temporary += ".partial";
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) {
      error = "cannot create the file";
      return false;
    }
    out << "PF\n" << image.width << ' ' << image.height << "\n-1.0\n";
    std::vector<float> row(std::size_t(image.width) * 3);
    for (std::uint32_t y = image.height; y-- > 0;) {
      for (std::uint32_t x = 0; x < image.width; ++x) {
        for (int c = 0; c < 3; ++c)
          row[x * 3 + c] = image.pixel(x, y)[c];
      }
      if constexpr (std::endian::native == std::endian::big)
        swapFloats(row);
      out.write(reinterpret_cast<const char*>(row.data()),
                std::streamsize(row.size() * sizeof(float)));
    }
    if (!out.flush()) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      error = "cannot write the file (disk full?)";
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    error = "cannot replace the file: " + ec.message();
    return false;
  }
  return true;
}

std::optional<HdrImage> tryReadPfm(const std::filesystem::path& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open the PFM file";
    return std::nullopt;
  }
  std::string magic;
  long long width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  if (!in || (magic != "PF" && magic != "Pf")) {
    error = "not a PFM file (expected a 'PF' or 'Pf' header)";
    return std::nullopt;
  }
  if (width <= 0 || height <= 0 || width > kMaxPfmSide || height > kMaxPfmSide || scale == 0.0) {
    error = "bad PFM header: size " + std::to_string(width) + "x" + std::to_string(height) +
            ", scale must be non-zero";
    return std::nullopt;
  }
  in.get();  // the single whitespace character that ends the header
  const int channels = magic == "PF" ? 3 : 1;
  const bool swap = (scale < 0) != (std::endian::native == std::endian::little);
  HdrImage image;
  image.width = std::uint32_t(width);
  image.height = std::uint32_t(height);
  image.rgba.resize(std::size_t(width) * height * 4);
  std::vector<float> row(std::size_t(width) * channels);
  for (std::uint32_t y = image.height; y-- > 0;) {
    in.read(reinterpret_cast<char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
    if (!in) {
      error = "the PFM file is truncated: expected " +
              std::to_string(width * height * channels * 4) + " bytes of pixels";
      return std::nullopt;
    }
    if (swap)
      swapFloats(row);
    for (std::uint32_t x = 0; x < image.width; ++x) {
      float* p = image.pixel(x, y);
      for (int c = 0; c < 3; ++c)
        p[c] = row[x * channels + (channels == 3 ? c : 0)];
      p[3] = 1.0f;
    }
  }
  return image;
}

void writePfm(const std::filesystem::path& path, const HdrImage& image) {
  std::string error;
  if (!tryWritePfm(path, image, error))
    throw std::runtime_error(path.string() + ": " + error);
}

HdrImage readPfm(const std::filesystem::path& path) {
  std::string error;
  std::optional<HdrImage> image = tryReadPfm(path, error);
  if (!image)
    throw std::runtime_error(path.string() + ": " + error);
  return std::move(*image);
}

}  // namespace memograph::runtime
