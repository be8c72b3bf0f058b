#include "compiler/library_files.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace memograph::compiler {

namespace fs = std::filesystem;

std::optional<std::vector<SourceFile>> readNodeLibraryDirectory(const std::string& directory,
                                                                Diagnostics& diagnostics) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    diagnostics.error(directory, "the node library directory does not exist");
    return std::nullopt;
  }
  std::vector<SourceFile> files;
  for (fs::recursive_directory_iterator it(directory, ec), end; it != end && !ec;
       it.increment(ec)) {
    if (!it->is_regular_file() || it->path().extension() != ".inc")
      continue;
    std::ifstream stream(it->path(), std::ios::binary);
    std::ostringstream text;
    text << stream.rdbuf();
    if (!stream) {
      diagnostics.error(it->path().string(), "cannot read this node library file");
      return std::nullopt;
    }
    files.push_back({fs::relative(it->path(), directory).generic_string(), text.str()});
  }
  if (ec) {
    diagnostics.error(directory, "cannot list the node library: " + ec.message());
    return std::nullopt;
  }
  if (files.empty()) {
    diagnostics.error(directory, "the node library directory has no .inc files");
    return std::nullopt;
  }
  std::sort(files.begin(), files.end(),
            [](const SourceFile& a, const SourceFile& b) { return a.path < b.path; });
  return files;
}

}  // namespace memograph::compiler
