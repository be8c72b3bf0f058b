#include "frame_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "runtime/host/image.h"
#endif
#ifdef MEMOGRAPH_HAVE_IO
#include "tools/io/image_io.h"
#endif

namespace memograph::cli {

std::optional<FramePattern> parseFramePattern(const std::string& out, std::string& error) {
  FramePattern result;
  result.pattern = out;
  const std::size_t slash = out.rfind('/');
  const std::size_t nameAt = slash == std::string::npos ? 0 : slash + 1;
  for (std::size_t i = out.find('#', nameAt); i != std::string::npos; i = out.find('#', i)) {
    if (result.hashesAt != std::string::npos) {
      error = "--out '" + out +
              "' has more than one run of '#' in its file name; one run is the frame's index";
      return std::nullopt;
    }
    result.hashesAt = i;
    while (i < out.size() && out[i] == '#')
      ++i;
    result.hashes = i - result.hashesAt;
  }
  return result;
}

std::string framePath(const FramePattern& pattern, std::uint32_t frame) {
  if (pattern.hashesAt == std::string::npos)
    return pattern.pattern;
  std::string index = std::to_string(frame);
  if (index.size() < pattern.hashes)
    index.insert(0, pattern.hashes - index.size(), '0');
  std::string path = pattern.pattern;
  path.replace(pattern.hashesAt, pattern.hashes, index);
  return path;
}

bool imageFileComplete(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return false;
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
#ifdef MEMOGRAPH_HAVE_RUNTIME
  if (extension == ".pfm") {
    std::string error;
    return runtime::tryReadPfm(path, error).has_value();
  }
#endif
#ifdef MEMOGRAPH_HAVE_IO
  compiler::Diagnostics diagnostics;
  return io::readImageFloat(path, diagnostics).has_value();
#else
  return false;
#endif
}

}  // namespace memograph::cli
