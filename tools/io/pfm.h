// Portable float map (PFM) files with diagnostics, for the io library's conversions (the
// core renderer has its own PFM writer for the GPU machine, where no image library
// travels; these read what it writes).
// Format: "PF" (RGB) or "Pf" (grey), width height, a scale whose sign gives the byte order
// (negative: little-endian), then 32-bit floats row by row, bottom row first.
#pragma once

#include <optional>
#include <string>

#include "compiler/diagnostics.h"
#include "runtime/scenes/float_image.h"

namespace memograph::io {

// Writes RGB (alpha dropped), little-endian. Writes to a temporary file next to `path` and
// renames it, so a failure leaves no partial file. Returns false after adding an error.
bool writePfm(const std::string& path, const runtime::FloatImage& image,
              compiler::Diagnostics& diagnostics);

// Reads "PF" or "Pf" in either byte order; alpha is 1. Errors name the file and the problem.
std::optional<runtime::FloatImage> readPfm(const std::string& path,
                                           compiler::Diagnostics& diagnostics);

}  // namespace memograph::io
