// Portable float map (PFM) files: the image format the renderer writes where no image
// library travels (the GPU machine); the io library converts them to PNG or EXR.
// Format: "PF" (RGB) or "Pf" (grey), width height, a scale whose sign gives the byte order
// (negative: little-endian), then 32-bit floats row by row, bottom row first.
#pragma once

#include <optional>
#include <string>

#include "compiler/diagnostics.h"
#include "runtime/scenes/float_image.h"

namespace memograph::runtime {

// Writes RGB (alpha dropped), little-endian. Writes to a temporary file next to `path` and
// renames it, so a failure leaves no partial file. Returns false after adding an error.
bool writePfm(const std::string& path, const FloatImage& image, compiler::Diagnostics& diagnostics);

// Reads "PF" or "Pf" in either byte order; alpha is 1. Errors name the file and the problem.
std::optional<FloatImage> readPfm(const std::string& path, compiler::Diagnostics& diagnostics);

}  // namespace memograph::runtime
