// PFM files with diagnostics, for the io library and the CLI: the core's reader and writer
// (runtime/host/image.h, the project's one PFM implementation) with their errors as diagnostics
// naming the file.
#pragma once

#include <optional>
#include <string>

#include "compiler/diagnostics.h"
#include "runtime/host/image.h"

namespace memograph::io {

// runtime::tryWritePfm: RGB, little-endian, atomic (no partial file). Returns false after
// adding an error.
bool writePfm(const std::string& path, const runtime::HdrImage& image,
              compiler::Diagnostics& diagnostics);

// runtime::tryReadPfm: "PF" or "Pf" in either byte order; alpha is 1.
std::optional<runtime::HdrImage> readPfm(const std::string& path,
                                         compiler::Diagnostics& diagnostics);

}  // namespace memograph::io
