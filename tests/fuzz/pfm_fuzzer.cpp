// libFuzzer entry point: any bytes as a PFM file through the project's one PFM reader
// (runtime::tryParsePfm). A header must never make it allocate more than the file holds
// (run with -rss_limit_mb), and a read image must have the size its header declared.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "runtime/host/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string error;
  const auto image = memograph::runtime::tryParsePfm(
      std::string_view(reinterpret_cast<const char*>(data), size), error);
  if (!image) {
    if (error.empty())
      std::abort();  // rejected without saying why
    return 0;
  }
  if (image->width == 0 || image->height == 0 ||
      image->rgba.size() != std::size_t(image->width) * image->height * 4 ||
      std::size_t(image->width) * image->height * 4 > size)  // 4: the smallest pixel (grey)
    std::abort();
  return 0;
}
