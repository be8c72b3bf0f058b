#include "runtime/host/image.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "compiler/input_file.h"
#include "runtime/host/atomic_file.h"

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

std::string encodePfm(const HdrImage& image) {
  std::string bytes =
      "PF\n" + std::to_string(image.width) + ' ' + std::to_string(image.height) + "\n-1.0\n";
  const std::size_t header = bytes.size();
  bytes.resize(header + std::size_t(image.width) * image.height * 3 * sizeof(float));
  std::vector<float> row(std::size_t(image.width) * 3);
  std::size_t offset = header;
  for (std::uint32_t y = image.height; y-- > 0;) {
    for (std::uint32_t x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c)
        row[x * 3 + c] = image.pixel(x, y)[c];
    }
    if constexpr (std::endian::native == std::endian::big)
      swapFloats(row);
    std::memcpy(bytes.data() + offset, row.data(), row.size() * sizeof(float));
    offset += row.size() * sizeof(float);
  }
  return bytes;
}

bool tryWritePfm(const std::filesystem::path& path, const HdrImage& image, std::string& error) {
  if (image.width == 0 || image.height == 0 ||
      image.rgba.size() != std::size_t(image.width) * image.height * 4) {
    error = "cannot write PFM: the image is empty or its size does not match";
    return false;
  }
  return files::writeFileAtomically(path, encodePfm(image), error);
}

std::optional<HdrImage> tryReadPfm(const std::filesystem::path& path, std::string& error) {
  const auto bytes = files::readInputFile(path, files::kMaxImageFileBytes, "images", error);
  if (!bytes)
    return std::nullopt;
  return tryParsePfm(*bytes, error);
}

std::optional<HdrImage> tryParsePfm(std::string_view data, std::string& error) {
  const std::string_view* bytes = &data;
  std::istringstream in{std::string(data)};
  // The header: "PF" or "Pf", whitespace, width, height, scale, one whitespace character.
  std::string magic;
  in >> magic;
  if (magic != "PF" && magic != "Pf") {
    error = bytes->empty() ? "the PFM file is empty"
                           : "not a PFM file: it starts with '" +
                                 magic.substr(0, std::min<std::size_t>(magic.size(), 8)) +
                                 "', not 'PF' (colour) or 'Pf' (grey)";
    return std::nullopt;
  }
  long long width = 0, height = 0;
  if (!(in >> width >> height)) {
    error = "bad PFM header: after '" + magic + "' expected the width and height as numbers";
    return std::nullopt;
  }
  double scale = 0;
  if (!(in >> scale)) {
    error =
        "bad PFM header: after the size expected the scale (a number, negative for "
        "little-endian)";
    return std::nullopt;
  }
  if (width <= 0 || height <= 0 || width > kMaxPfmSide || height > kMaxPfmSide) {
    error = "bad PFM header: the size " + std::to_string(width) + "x" + std::to_string(height) +
            " is not within 1.." + std::to_string(kMaxPfmSide) + " a side";
    return std::nullopt;
  }
  if (std::uint64_t(width) * std::uint64_t(height) > files::kMaxImagePixels) {
    error = "the PFM image is " + std::to_string(width) + "x" + std::to_string(height) +
            ", over the limit of " + std::to_string(files::kMaxImagePixels) +
            " pixels (docs/guide/limits.md)";
    return std::nullopt;
  }
  if (scale == 0.0 || !std::isfinite(scale)) {
    error = "bad PFM header: the scale must be a non-zero number (its sign gives the byte order)";
    return std::nullopt;
  }
  in.get();  // the single whitespace character that ends the header
  const int channels = magic == "PF" ? 3 : 1;
  // Checked against the file before allocating: a header cannot make us allocate more
  // than the file holds.
  const std::uint64_t expected = std::uint64_t(width) * height * channels * sizeof(float);
  // A header that ends the file leaves the stream failed (tellg -1): no pixels follow.
  const std::streamoff position = in.tellg();
  const std::uint64_t header =
      position < 0 ? bytes->size() : std::min<std::uint64_t>(position, bytes->size());
  const std::uint64_t available = bytes->size() - header;
  if (available < expected) {
    error = "the PFM file is truncated: its header declares " + std::to_string(width) + "x" +
            std::to_string(height) + (channels == 3 ? " RGB" : " grey") + ", " +
            std::to_string(expected) + " bytes of pixels, but " + std::to_string(available) +
            " follow the header";
    return std::nullopt;
  }
  const bool swap = (scale < 0) != (std::endian::native == std::endian::little);
  HdrImage image;
  image.width = std::uint32_t(width);
  image.height = std::uint32_t(height);
  image.rgba.resize(std::size_t(width) * height * 4);
  std::vector<float> row(std::size_t(width) * channels);
  const char* pixels = bytes->data() + header;
  for (std::uint32_t y = image.height; y-- > 0;) {
    std::memcpy(row.data(), pixels, row.size() * sizeof(float));
    pixels += row.size() * sizeof(float);
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
