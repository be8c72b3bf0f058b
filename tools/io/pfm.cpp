#include "tools/io/pfm.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace memograph::io {
namespace {

std::uint32_t byteSwap(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

}  // namespace

bool writePfm(const std::string& path, const runtime::FloatImage& image,
              compiler::Diagnostics& diagnostics) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    diagnostics.error(path, "cannot write PFM: the image is empty or its size does not match");
    return false;
  }
  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) {
      diagnostics.error(path, "cannot create the file");
      return false;
    }
    out << "PF\n" << image.width << ' ' << image.height << "\n-1.0\n";
    std::vector<float> row(static_cast<std::size_t>(image.width) * 3);
    for (int y = image.height - 1; y >= 0; --y) {
      for (int x = 0; x < image.width; ++x) {
        for (int c = 0; c < 3; ++c)
          row[x * 3 + c] = image.pixel(x, y)[c];
      }
      if constexpr (std::endian::native == std::endian::big) {
        for (float& f : row)
          f = std::bit_cast<float>(byteSwap(std::bit_cast<std::uint32_t>(f)));
      }
      out.write(reinterpret_cast<const char*>(row.data()),
                static_cast<std::streamsize>(row.size() * sizeof(float)));
    }
    if (!out.flush()) {
      out.close();
      std::filesystem::remove(temporary);
      diagnostics.error(path, "cannot write the file (disk full?)");
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    diagnostics.error(path, "cannot replace the file: " + ec.message());
    return false;
  }
  return true;
}

std::optional<runtime::FloatImage> readPfm(const std::string& path,
                                           compiler::Diagnostics& diagnostics) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diagnostics.error(path, "cannot open the PFM file");
    return std::nullopt;
  }
  std::string magic;
  long long width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  if (!in || (magic != "PF" && magic != "Pf")) {
    diagnostics.error(path, "not a PFM file (expected a 'PF' or 'Pf' header)");
    return std::nullopt;
  }
  if (width <= 0 || height <= 0 || width > 65536 || height > 65536 || scale == 0.0) {
    diagnostics.error(path, "bad PFM header: size " + std::to_string(width) + "x" +
                                std::to_string(height) + ", scale must be non-zero");
    return std::nullopt;
  }
  in.get();  // the single whitespace character that ends the header
  const int channels = magic == "PF" ? 3 : 1;
  const bool swap = (scale < 0) != (std::endian::native == std::endian::little);
  runtime::FloatImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.rgba.resize(static_cast<std::size_t>(width) * height * 4);
  std::vector<float> row(static_cast<std::size_t>(width) * channels);
  for (int y = image.height - 1; y >= 0; --y) {
    in.read(reinterpret_cast<char*>(row.data()),
            static_cast<std::streamsize>(row.size() * sizeof(float)));
    if (!in) {
      diagnostics.error(path, "the PFM file is truncated: expected " +
                                  std::to_string(width * height * channels * 4) +
                                  " bytes of pixels");
      return std::nullopt;
    }
    if (swap) {
      for (float& f : row)
        f = std::bit_cast<float>(byteSwap(std::bit_cast<std::uint32_t>(f)));
    }
    for (int x = 0; x < image.width; ++x) {
      float* p = image.pixel(x, y);
      for (int c = 0; c < 3; ++c)
        p[c] = row[x * channels + (channels == 3 ? c : 0)];
      p[3] = 1.0f;
    }
  }
  return image;
}

}  // namespace memograph::io
