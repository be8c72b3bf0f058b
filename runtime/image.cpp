#include "runtime/image.h"

#include <algorithm>
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

void writePfm(const std::filesystem::path& path, const HdrImage& image) {
  std::ofstream out(path, std::ios::binary);
  if (!out)
    throw std::runtime_error("cannot write " + path.string());
  out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
  std::vector<float> row(std::size_t(image.width) * 3);
  for (std::uint32_t y = image.height; y-- > 0;) {
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      row[x * 3 + 0] = p[0];
      row[x * 3 + 1] = p[1];
      row[x * 3 + 2] = p[2];
    }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * 4));
  }
  if (!out)
    throw std::runtime_error("cannot write " + path.string());
}

HdrImage readPfm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("cannot open " + path.string());
  std::string magic;
  double scale = 0;
  HdrImage image;
  in >> magic >> image.width >> image.height >> scale;
  in.get();
  if (!in || (magic != "PF" && magic != "Pf") || image.width == 0 || image.height == 0 ||
      scale == 0) {
    throw std::runtime_error(path.string() + ": not a PFM file (expected 'PF' or 'Pf' header)");
  }
  if (scale > 0)
    throw std::runtime_error(path.string() + ": big-endian PFM is not supported");
  int channels = magic == "PF" ? 3 : 1;
  std::vector<float> data(std::size_t(image.width) * image.height * channels);
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * 4));
  if (!in)
    throw std::runtime_error(path.string() + ": truncated PFM data");
  image.rgba.resize(std::size_t(image.width) * image.height * 4);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    std::uint32_t fileRow = image.height - 1 - y;
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const float* s = &data[(std::size_t(fileRow) * image.width + x) * channels];
      float* d = image.pixel(x, y);
      d[0] = s[0];
      d[1] = s[channels == 3 ? 1 : 0];
      d[2] = s[channels == 3 ? 2 : 0];
      d[3] = 1.0f;
    }
  }
  return image;
}

}  // namespace memograph::runtime
