#include "tools/io/image_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "compiler/input_file.h"
#include "tools/io/pfm.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

float tonemap(float x, Tonemap curve) {
  x = std::max(x, 0.0f);
  switch (curve) {
    case Tonemap::Clamp:
      return std::min(x, 1.0f);
    case Tonemap::Reinhard:
      return x / (1.0f + x);
    case Tonemap::Aces: {
      // Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
      const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
      return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
    }
  }
  return std::min(x, 1.0f);
}

// Reads all pixels as RGBA of `type`, expanding grey and RGB; shared by both readers.
template <typename T>
bool readRgba(const std::string& path, OIIO::TypeDesc type, T alphaOne, int& width, int& height,
              std::vector<T>& rgba, compiler::Diagnostics& diagnostics) {
  std::string fileError;
  if (!files::checkInputFile(path, files::kMaxImageFileBytes, "images", fileError)) {
    diagnostics.error(path, fileError);
    return false;
  }
  // Keep colour and alpha as stored: OpenImageIO would otherwise premultiply PNG colours.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) {
    diagnostics.error(path, "cannot read the image: " + OIIO::geterror());
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  const int channels = spec.nchannels;
  if (width <= 0 || height <= 0 || channels <= 0) {
    diagnostics.error(path, "the image has no pixels");
    return false;
  }
  // The header's size is checked before any allocation: a few bytes may declare gigapixels.
  if (std::uint64_t(width) * std::uint64_t(height) > files::kMaxImagePixels || channels > 64) {
    diagnostics.error(path, "the image declares " + std::to_string(width) + "x" +
                                std::to_string(height) + " pixels with " +
                                std::to_string(channels) + " channels, over the limit of " +
                                std::to_string(files::kMaxImagePixels) +
                                " pixels and 64 channels (docs/guide/limits.md)");
    return false;
  }
  std::vector<T> raw;
  try {
    raw.resize(static_cast<std::size_t>(width) * height * channels);
    rgba.resize(static_cast<std::size_t>(width) * height * 4);
  } catch (const std::bad_alloc&) {
    diagnostics.error(path, "not enough memory for the image's " + std::to_string(width) + "x" +
                                std::to_string(height) + " pixels");
    return false;
  }
  if (!in->read_image(0, 0, 0, channels, type, raw.data())) {
    diagnostics.error(path, "cannot decode the image: " + in->geterror());
    return false;
  }
  in->close();
  for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p) {
    const T* s = &raw[p * channels];
    T* d = &rgba[p * 4];
    if (channels <= 2) {  // grey (+ alpha)
      d[0] = d[1] = d[2] = s[0];
      d[3] = channels == 2 ? s[1] : alphaOne;
    } else {
      d[0] = s[0];
      d[1] = s[1];
      d[2] = s[2];
      d[3] = channels >= 4 ? s[3] : alphaOne;
    }
  }
  return true;
}

}  // namespace

std::uint8_t toSrgb8(float linear, const LdrOptions& ldr) {
  const float x = tonemap(linear * std::exp2(ldr.exposure), ldr.tonemap);
  // The sRGB transfer function (IEC 61966-2-1).
  const float srgb = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(std::clamp(srgb, 0.0f, 1.0f) * 255.0f));
}

bool writeImage(const std::string& path, const runtime::HdrImage& image, const LdrOptions& ldr,
                compiler::Diagnostics& diagnostics) {
  files::StagedFile staged;
  return stageImage(path, image, ldr, staged, diagnostics) && commitImage(staged, diagnostics);
}

bool stageImage(const std::string& path, const runtime::HdrImage& image, const LdrOptions& ldr,
                files::StagedFile& staged, compiler::Diagnostics& diagnostics) {
  if (image.width == 0 || image.height == 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    diagnostics.error(path, "cannot write an empty image, or one whose size does not match");
    return false;
  }
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr") {
    diagnostics.error(path, "unsupported image extension '" + ext + "'")
        .notes.push_back("write .png (8-bit sRGB) or .exr (float)");
    return false;
  }
  // A unique temporary (files::StagedFile) that keeps the extension: OpenImageIO picks the
  // format from it, and concurrent writers of one path never share it.
  std::string error;
  if (!staged.create(path, error)) {
    diagnostics.error(path, error);
    return false;
  }
  const std::string temporary = staged.temporaryPath().string();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    diagnostics.error(path, "cannot create an image writer: " + OIIO::geterror());
    return false;
  }
  bool ok = false;
  if (ext == ".png") {
    std::vector<std::uint8_t> pixels(image.rgba.size());
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
      pixels[i] = (i % 4 == 3) ? static_cast<std::uint8_t>(
                                     std::lround(std::clamp(image.rgba[i], 0.0f, 1.0f) * 255.0f))
                               : toSrgb8(image.rgba[i], ldr);
    }
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // Our colours are not premultiplied: without this the PNG writer divides by alpha.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    ok = out->open(temporary, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) &&
         out->close();
  } else {
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:ColorSpace", "Linear");
    ok = out->open(temporary, spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.rgba.data()) &&
         out->close();
  }
  if (!ok) {
    const std::string cause = out->geterror();
    diagnostics.error(path, "cannot write the image" + (cause.empty() ? "" : ": " + cause));
    staged.discard();
    return false;
  }
  // OpenImageIO reports some write errors (a full disk) only through the stream: fsync
  // finds them before the rename.
  if (!staged.sync(error)) {
    diagnostics.error(path, error);
    staged.discard();
    return false;
  }
  return true;
}

bool commitImage(files::StagedFile& staged, compiler::Diagnostics& diagnostics) {
  std::string error;
  if (!staged.commit(error)) {
    diagnostics.error(staged.target().string(), error);
    return false;
  }
  return true;
}

bool writeRgbImage(const std::string& path, std::uint32_t width, std::uint32_t height,
                   const std::vector<float>& rgb, RgbEncoding encoding,
                   compiler::Diagnostics& diagnostics) {
  if (width == 0 || height == 0 || rgb.size() != std::size_t(width) * height * 3) {
    diagnostics.error(path, "cannot write an empty image, or one whose size does not match");
    return false;
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    diagnostics.error(path, "cannot create an image writer: " + OIIO::geterror());
    return false;
  }
  bool ok = false;
  if (encoding == RgbEncoding::Float) {
    OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:ColorSpace", "Linear");
    ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) &&
         out->close();
  } else {
    std::vector<std::uint8_t> pixels(rgb.size());
    for (std::size_t i = 0; i < rgb.size(); ++i) {
      pixels[i] =
          encoding == RgbEncoding::Srgb8
              ? toSrgb8(rgb[i], LdrOptions{})
              : static_cast<std::uint8_t>(std::lround(std::clamp(rgb[i], 0.0f, 1.0f) * 255.0f));
    }
    OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", encoding == RgbEncoding::Srgb8 ? "sRGB" : "Linear");
    ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) &&
         out->close();
  }
  if (!ok) {
    diagnostics.error(path, "cannot write the image: " + out->geterror());
    std::error_code ec;
    fs::remove(path, ec);
    return false;
  }
  return true;
}

std::optional<Rgba8Image> readImageRgba8(const std::string& path,
                                         compiler::Diagnostics& diagnostics) {
  Rgba8Image image;
  if (!readRgba<std::uint8_t>(path, OIIO::TypeDesc::UINT8, 255, image.width, image.height,
                              image.rgba, diagnostics)) {
    return std::nullopt;
  }
  return image;
}

std::optional<runtime::HdrImage> readImageFloat(const std::string& path,
                                                compiler::Diagnostics& diagnostics) {
  runtime::HdrImage image;
  int width = 0, height = 0;
  if (!readRgba<float>(path, OIIO::TypeDesc::FLOAT, 1.0f, width, height, image.rgba, diagnostics)) {
    return std::nullopt;
  }
  image.width = std::uint32_t(width);
  image.height = std::uint32_t(height);
  return image;
}

bool convertPfm(const std::string& pfmPath, const std::string& outPath, const LdrOptions& ldr,
                compiler::Diagnostics& diagnostics) {
  const auto image = readPfm(pfmPath, diagnostics);
  return image && writeImage(outPath, *image, ldr, diagnostics);
}

}  // namespace memograph::io
