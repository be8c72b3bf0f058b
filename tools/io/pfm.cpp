#include "tools/io/pfm.h"

namespace memograph::io {

bool writePfm(const std::string& path, const runtime::HdrImage& image,
              compiler::Diagnostics& diagnostics) {
  std::string error;
  if (runtime::tryWritePfm(path, image, error))
    return true;
  diagnostics.error(path, error);
  return false;
}

std::optional<runtime::HdrImage> readPfm(const std::string& path,
                                         compiler::Diagnostics& diagnostics) {
  std::string error;
  std::optional<runtime::HdrImage> image = runtime::tryReadPfm(path, error);
  if (!image)
    diagnostics.error(path, error);
  return image;
}

}  // namespace memograph::io
