#include "compiler/library_files.h"

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compiler/input_file.h"

namespace memograph::compiler {

namespace fs = std::filesystem;

// Bounds the work a library folder can cause (docs/guide/limits.md).
constexpr std::size_t kMaxNodeLibraryFiles = 4096;
constexpr std::uint64_t kMaxNodeLibraryBytes = 64 * files::kMiB;

std::optional<std::string> nodeLibraryDirectoryProblem(const std::string& directory) {
  if (directory.empty())
    return "the node library directory is an empty path";
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  if (ec && ec.value() != ENOENT)
    return "cannot open the node library: " + files::describeFileError(ec);
  if (!fs::exists(status))
    return std::string("the node library directory does not exist");
  if (!fs::is_directory(status))
    return std::string("the node library must be a folder of .inc files; this is a file");
  return std::nullopt;
}

std::optional<std::vector<SourceFile>> readNodeLibraryDirectory(const std::string& directory,
                                                                Diagnostics& diagnostics) {
  if (const auto problem = nodeLibraryDirectoryProblem(directory)) {
    diagnostics.error(directory, *problem);
    return std::nullopt;
  }
  std::error_code ec;
  std::vector<SourceFile> files;
  std::uint64_t totalBytes = 0;
  for (fs::recursive_directory_iterator it(directory, ec), end; it != end && !ec;
       it.increment(ec)) {
    if (it->path().extension() != ".inc")
      continue;
    std::error_code typeError;
    // A folder named *.inc is a mistake (a file that was meant), not something to skip.
    if (it->is_directory(typeError)) {
      diagnostics.error(it->path().string(),
                        "is a folder, but .inc names node library files; rename it");
      return std::nullopt;
    }
    std::string error;
    auto text =
        files::readInputFile(it->path(), files::kMaxTextFileBytes, "node library files", error);
    if (!text) {
      diagnostics.error(it->path().string(), "cannot read this node library file: " + error);
      return std::nullopt;
    }
    totalBytes += text->size();
    if (totalBytes > kMaxNodeLibraryBytes) {
      diagnostics.error(directory, "the node library's .inc files hold more than " +
                                       files::formatBytes(kMaxNodeLibraryBytes) +
                                       " in all (docs/guide/limits.md)");
      return std::nullopt;
    }
    files.push_back({fs::relative(it->path(), directory).generic_string(), std::move(*text)});
    if (files.size() > kMaxNodeLibraryFiles) {
      diagnostics.error(directory, "the node library has more than " +
                                       std::to_string(kMaxNodeLibraryFiles) +
                                       " .inc files (docs/guide/limits.md)");
      return std::nullopt;
    }
  }
  if (ec) {
    diagnostics.error(directory, "cannot list the node library: " + files::describeFileError(ec));
    return std::nullopt;
  }
  if (files.empty()) {
    diagnostics.error(directory, "the node library directory has no .inc files");
    return std::nullopt;
  }
  // The prelude (types, helpers every node uses) must be there: without it the library
  // loads but every generated include is unusable shader code.
  if (std::none_of(files.begin(), files.end(),
                   [](const SourceFile& f) { return f.path.starts_with("prelude/"); })) {
    diagnostics.error(directory, "the node library has no prelude/ folder of .inc files")
        .notes.push_back("copy nodes/prelude/ from the built-in library and edit it");
    return std::nullopt;
  }
  std::sort(files.begin(), files.end(),
            [](const SourceFile& a, const SourceFile& b) { return a.path < b.path; });
  return files;
}

}  // namespace memograph::compiler
