// Image files through OpenImageIO: PNG (tonemapped, sRGB, 8-bit) and EXR (linear float)
// output from the renderer's RGBA float buffer, texture input as RGBA8 or float, and the
// conversion of the PFM files the GPU machine writes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "runtime/host/atomic_file.h"
#include "runtime/host/image.h"

namespace memograph::io {

struct Rgba8Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width*height*4, top row first, as stored in the file
};

enum class Tonemap {
  Clamp,     // x → min(x, 1): exact below 1, for tests and calibrated images
  Reinhard,  // x / (1 + x) per channel
  Aces,      // Narkowicz's fit of the ACES filmic curve (2015)
};

// How float radiance becomes 8-bit: scaled by 2^exposure, tonemapped, sRGB-encoded.
// Alpha is clamped to [0, 1] and stored linearly.
struct LdrOptions {
  float exposure = 0.0f;
  Tonemap tonemap = Tonemap::Clamp;
};

// Writes by extension: .png (8-bit sRGB via `ldr`), .exr (32-bit float, linear, `ldr`
// ignored). Writes to a unique temporary file next to `path` and renames it
// (files::StagedFile), so an error leaves no partial file and concurrent writers of one
// path leave one complete image. Returns false after adding an error naming the path.
bool writeImage(const std::string& path, const runtime::HdrImage& image, const LdrOptions& ldr,
                compiler::Diagnostics& diagnostics);
// writeImage in two steps, for outputs committed as a set (files::commitFileSet): the
// image is written to `staged`'s temporary, and commitImage renames it into place.
bool stageImage(const std::string& path, const runtime::HdrImage& image, const LdrOptions& ldr,
                files::StagedFile& staged, compiler::Diagnostics& diagnostics);
bool commitImage(files::StagedFile& staged, compiler::Diagnostics& diagnostics);

// How writeRgbImage stores its floats: 32-bit float (.exr), or 8-bit (.png) either
// sRGB-encoded (colours) or linear (data: scalars, encoded normals); 8-bit values are
// clamped to [0, 1] and rounded.
enum class RgbEncoding { Float, Srgb8, Linear8 };

// Writes `rgb` (width*height*3 floats, top row first) straight to `path` as .exr (RGB,
// 32-bit float, values exact) or .png (RGB, 8-bit): no temporary file, so callers that
// commit several files as a set (memograph bake) write temporaries and rename them.
// Returns false after adding an error naming the path.
bool writeRgbImage(const std::string& path, std::uint32_t width, std::uint32_t height,
                   const std::vector<float>& rgb, RgbEncoding encoding,
                   compiler::Diagnostics& diagnostics);

// Reads any format OpenImageIO knows as RGBA (missing channels: grey→RGB, alpha 1).
std::optional<Rgba8Image> readImageRgba8(const std::string& path,
                                         compiler::Diagnostics& diagnostics);
std::optional<runtime::HdrImage> readImageFloat(const std::string& path,
                                                compiler::Diagnostics& diagnostics);

// Reads a PFM written by the renderer and writes it as `outPath` (.png or .exr).
bool convertPfm(const std::string& pfmPath, const std::string& outPath, const LdrOptions& ldr,
                compiler::Diagnostics& diagnostics);

// The 8-bit value of one linear channel under `ldr` (exposed for tests).
std::uint8_t toSrgb8(float linear, const LdrOptions& ldr);

}  // namespace memograph::io
